#!/usr/bin/env bash
# The validity-bit study (docs/results/validity-bit-study/, written up in
# docs/findings.md): every method on four workloads, 32 designs of the `small`
# preset, through `vbsim explore scripts/explore/validity-bit-study.json`.
#   1. subdivides the bundled Wuson three times (238,848 triangles,
#      scripts/subdivide_mesh.py) and captures embree-tools' `pathtracer` on it
#      (320x240, 4 samples, offsets stripped: docs/capture.md);
#   2. runs the exploration (the capture through the oracle, a closed-loop frame,
#      two generated scenarios; points cached in build/results/study/explore/points/);
#   3. copies report.md, points.csv and the charts to docs/results/validity-bit-study/.
#
#   scripts/validity_bit_study.sh [--jobs N] [--backend slurm [--partition P] ...]
# Options go to `vbsim explore` (docs/explore.md). About 10 minutes on 2 cores.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash scripts/setup.sh
vbsim=build/vbsim
out=build/results/study
mkdir -p "$out"

/usr/bin/python3 scripts/subdivide_mesh.py traces/wuson/WusonOBJ.obj 3 -o "$out/wuson239k.obj"
rm -rf "$out/wuson-capture"
"$vbsim" capture --binary --strip-offsets -o "$out/wuson-capture" -- pathtracer -i "$out/wuson239k.obj" \
  --size 320 240 --spp 4 --ambientlight 0.3 0.3 0.3 --pointlight 3 5 3 30 30 30 \
  -o "$out/wuson-capture/image.ppm" --threads 2 --vp 4 1.2 1 --vi 0 0.75 -0.4 --fov 35

"$vbsim" explore scripts/explore/validity-bit-study.json -o "$out/explore" "$@"

dest=docs/results/validity-bit-study
rm -rf "$dest.part"
mkdir -p "$dest.part"
cp "$out/explore/report.md" "$out/explore/points.csv" "$out"/explore/*.png "$dest.part/"
rm -rf "$dest"
mv "$dest.part" "$dest"
echo "validity_bit_study.sh: wrote $dest/report.md, points.csv and charts" >&2
