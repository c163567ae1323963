#!/usr/bin/env bash
# Regenerates every committed result in docs/results/ with one command:
#  1. accuracy.md: generates every scenario `vbsim scenarios` lists into
#     build/results/scenarios/FAMILY with a fixed seed (random-triangles as
#     three families, one per protocol) and scores all of them with every method
#     and all three testers in cycle mode (`vbsim score --mode cycle`: the
#     three-half-plane configurations also timed by the cycle-level model on the
#     small preset, in the same run); the full table also goes to
#     build/results/accuracy.json;
#  2. pbrt-protocol.md: pbrt-v4's Reintersect protocol at pbrt's size and at
#     100 times it (scripts/pbrt_protocol.py);
#  3. architecture.md and arch-*.png: the cycle-level model swept over its
#     knobs, the presets' predictions, and every method's cycles per ray on the
#     same scenario families (scripts/arch_sweep.py);
#  4. pareto.md and pareto-*.png: speed against accuracy, drawn from the one
#     table of step 1 (scripts/pareto.py);
#     energy.md: energy against accuracy for the families and a captured
#     pathtracer trace (scripts/energy_page.py, docs/energy.md);
#  5. stability.md, sweep-*.png, sweeps.csv: stability sweeps (scripts/sweep.py);
#  6. montage.png: every method rendered on the failure scenes
#     (scripts/make_montage.py); closed-loop.md and closed-loop*.png: every
#     method's frame on the accelerator, closed loop against replay of the
#     reference renderer's rays (scripts/closed_loop_study.py);
#  7. the validity-bit study (scripts/validity_bit_study.sh, vbsim explore):
#     docs/results/validity-bit-study/;
#  8. checks every figure docs/findings.md quotes against them
#     (scripts/check_findings.py, full mode): exits 1 when one no longer matches.
#
#   scripts/make_results.sh [--rays N] [--seed S] [--backend slurm [--partition P]
#                           [--account A] [--time T] [--max-parallel N]]
#
# --rays (default 10000) is passed to every scenario's `vbsim gen --rays`; a
# scenario whose rays mean something costlier gets its own count in rays_for()
# below. Same arguments, same files (but for the measured speeds and the
# provenance each file records). --backend slurm runs the score (one point per
# family, scripts/score_points.py), the architecture and the stability sweeps
# as Slurm job arrays (docs/cluster.md); the build folder must be on a file
# system the compute nodes share.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

rays=10000
seed=1
args=()
backend=()  # passed to the scripts that run points (scripts/point_jobs.py)
while (($#)); do
  case "$1" in
    --rays) rays="$2"; args+=("$1" "$2"); shift 2 ;;
    --seed) seed="$2"; args+=("$1" "$2"); shift 2 ;;
    --backend|--partition|--account|--time|--max-parallel) backend+=("$1" "$2"); shift 2 ;;
    *) echo "make_results.sh: unknown argument '$1' (use --rays N, --seed S, --backend slurm ...)" >&2; exit 2 ;;
  esac
done

# Per-family ray counts where the common one does not fit: a random-triangles
# "ray" is a triangle with its own scene and trace and about ten rays (pbrt-v4:
# N/10 = 1000 triangles, pbrt's own count, with 8 + 8 children each).
rays_for() {
  case "$1" in
    random-triangles-rtg) echo $((rays / 5)) ;;
    random-triangles-pbrt|random-triangles-pbrt-v4) echo $((rays / 10)) ;;
    *) echo "$rays" ;;
  esac
}

# The families of a scenario: FAMILY and its extra `vbsim gen` arguments.
families_of() {
  case "$1" in
    random-triangles) echo "random-triangles-rtg --set protocol=rtg"
                      echo "random-triangles-pbrt --set protocol=pbrt"
                      echo "random-triangles-pbrt-v4 --set protocol=pbrt-v4" ;;
    paths) echo "paths"
           echo "paths-wuson --set scene=traces/wuson/WusonOBJ.obj" ;;
    *) echo "$1" ;;
  esac
}

bash scripts/setup.sh
vbsim=build/vbsim
out=build/results
rm -rf "$out/scenarios"
mkdir -p "$out/scenarios"

dirs=()
for scenario in $("$vbsim" scenarios --names); do
  while read -r family extra; do
    # shellcheck disable=SC2086 # extra holds separate words
    "$vbsim" gen "$scenario" --rays "$(rays_for "$family")" --seed "$seed" $extra \
      -q -o "$out/scenarios/$family"
    dirs+=("$out/scenarios/$family")
  done < <(families_of "$scenario")
done

testers=three-half-plane,moller-trumbore,pbrt-watertight
cycle=(--mode cycle --preset small --cycle-testers three-half-plane)
regenerate="scripts/make_results.sh${args[*]:+ ${args[*]}}"
if ((${#backend[@]})); then
  /usr/bin/python3 scripts/score_points.py "${dirs[@]}" --vbsim "$vbsim" --testers "$testers" "${cycle[@]}" \
    --out "$out/accuracy.json" --accuracy-md docs/results/accuracy.md --regenerate-with "$regenerate" "${backend[@]}"
else
  "$vbsim" score "${dirs[@]}" --testers "$testers" "${cycle[@]}" --out "$out/accuracy.json" \
    --accuracy-md docs/results/accuracy.md --regenerate-with "$regenerate" > "$out/score.txt"
fi
echo "make_results.sh: wrote docs/results/accuracy.md and $out/accuracy.json" >&2

/usr/bin/python3 scripts/pbrt_protocol.py --vbsim "$vbsim" --out docs/results --results "$out"

/usr/bin/python3 scripts/arch_sweep.py --vbsim "$vbsim" --families "${dirs[@]}" --out docs/results \
  --results "$out" ${backend[@]+"${backend[@]}"}
/usr/bin/python3 scripts/pareto.py --score "$out/accuracy.json" --out docs/results
# A captured trace of embree-tools' pathtracer on the bunny (docs/capture.md), scored
# for the energy page next to the families.
rm -rf "$out/captured"
"$vbsim" capture --strip-offsets -o "$out/captured/raw" -- pathtracer -i traces/bunny/bunny.obj --size 160 120 \
  --spp 1 --ambientlight 0.3 0.3 0.3 --pointlight 10 20 20 300 300 300 -o "$out/captured/raw/image.ppm" \
  --threads 1 --vp 0 5 25 --vi 0 4.8 0 --fov 30 > /dev/null
mkdir -p "$out/captured/pathtracer"
"$vbsim" oracle -q "$out/captured/raw/trace.jsonl" -o "$out/captured/pathtracer/trace.jsonl"
"$vbsim" score -q "$out/captured/pathtracer" --testers "$testers" --out "$out/pathtracer.json" > /dev/null
/usr/bin/python3 scripts/energy_page.py --score "$out/accuracy.json" --score "$out/pathtracer.json" --out docs/results
/usr/bin/python3 scripts/sweep.py --vbsim "$vbsim" --work "$out/sweeps" --out docs/results ${backend[@]+"${backend[@]}"}
/usr/bin/python3 scripts/make_montage.py
# Closed loop against replay of the reference renderer's rays, every method (docs/render.md).
/usr/bin/python3 scripts/closed_loop_study.py --vbsim "$vbsim"
# The timing cross-validation against rtcore-systemc: only where its source is given
# (VBSIM_RTCORE_SRC); skipped with a message otherwise, leaving the page as it was.
/usr/bin/python3 scripts/rtcore_crossval.py --vbsim "$vbsim"
# The validity-bit study: every method at equal area and equal throughput on a captured
# path tracer over 238,848 triangles and three other workloads (vbsim explore).
bash scripts/validity_bit_study.sh ${backend[@]+"${backend[@]}"}
echo "make_results.sh: every result in docs/results/ regenerated" >&2
# Every figure docs/findings.md quotes against the regenerated results and its own
# reruns (scripts/check_findings.py): a figure that moved fails here, and the page
# must be updated with it.
/usr/bin/python3 scripts/check_findings.py --vbsim "$vbsim"
