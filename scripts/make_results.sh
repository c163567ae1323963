#!/usr/bin/env bash
# Regenerates the committed accuracy results (docs/results/accuracy.md): builds
# vbsim, generates every scenario `vbsim scenarios` lists into
# build/results/scenarios/NAME with a fixed seed, and scores all of them with
# every method and both testers (`vbsim score`). The full table is also written
# as JSON to build/results/accuracy.json.
#
#   scripts/make_results.sh [--rays N] [--seed S]
#
# --rays (default 10000) is passed to every scenario's `vbsim gen --rays`; a
# scenario whose rays mean something costlier can get its own count in
# rays_for() below. Same arguments, same files.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

rays=10000
seed=1
args=()
while (($#)); do
  case "$1" in
    --rays) rays="$2"; args+=("$1" "$2"); shift 2 ;;
    --seed) seed="$2"; args+=("$1" "$2"); shift 2 ;;
    *) echo "make_results.sh: unknown argument '$1' (use --rays N, --seed S)" >&2; exit 2 ;;
  esac
done

# Per-scenario ray counts where the common one does not fit (none so far).
rays_for() {
  case "$1" in
    *) echo "$rays" ;;
  esac
}

bash scripts/setup.sh
vbsim=build/vbsim
out=build/results
rm -rf "$out/scenarios"
mkdir -p "$out/scenarios"

dirs=()
for scenario in $("$vbsim" scenarios --names); do
  "$vbsim" gen "$scenario" --rays "$(rays_for "$scenario")" --seed "$seed" -o "$out/scenarios/$scenario"
  dirs+=("$out/scenarios/$scenario")
done

"$vbsim" score "${dirs[@]}" --out "$out/accuracy.json" --accuracy-md docs/results/accuracy.md \
  --regenerate-with "scripts/make_results.sh${args[*]:+ ${args[*]}}"
echo "make_results.sh: wrote docs/results/accuracy.md and $out/accuracy.json" >&2
