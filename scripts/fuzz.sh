#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, AddressSanitizer + UndefinedBehaviorSanitizer)
# in build-fuzz/ and runs each for a set time from its committed seed corpus
# (testbench/fuzz/corpus/TARGET/), one after the other.
#   scripts/fuzz.sh [--seconds N] [TARGET...]   (default: 120 s per target, every target)
# Targets: text_trace binary_trace rtcore_rays config scene_ply scene_obj. Every target but
# rtcore_rays has a structure-aware mutator beside libFuzzer's byte mutations
# (testbench/fuzz/structured_mutator.h): deep nesting, extreme numbers, lying counts and
# header lengths, repeated keys.
# New inputs go to a scratch corpus (build-fuzz/corpus/TARGET/), never into the
# repository; crashes, timeouts and out-of-memory inputs are kept in
# build-fuzz/findings/TARGET/ and named on stderr. Prints per target the
# executions, the new coverage and the findings, and writes them to
# build-fuzz/fuzz-summary.md. A finding becomes a regression test in the suite
# (docs/reliability.md). Exits 1 when any target found something.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds=120
targets=()
while (($#)); do
  case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) targets+=("$1"); shift ;;
  esac
done
((${#targets[@]})) || targets=(text_trace binary_trace rtcore_rays config scene_ply scene_obj)

build="${VBSIM_FUZZ_BUILD_DIR:-$root/build-fuzz}"
VBSIM_FUZZ=1 VBSIM_BUILD_DIR="$build" \
  VBSIM_CMAKE_ARGS="-DVBSIM_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang" "$root/scripts/setup.sh"

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
summary="$build/fuzz-summary.md"
{
  echo "| target | seconds | executions | exec/s | coverage (edges) | corpus | crashes | timeouts | out of memory |"
  echo "|---|---|---|---|---|---|---|---|---|"
} > "$summary"
found=0
for t in "${targets[@]}"; do
  program="$build/fuzz/fuzz_$t"
  [ -x "$program" ] || { echo "fuzz: no target '$t' ($program)" >&2; exit 2; }
  corpus="$build/corpus/$t"
  findings="$build/findings/$t"
  mkdir -p "$corpus" "$findings"
  cp -n "$root/testbench/fuzz/corpus/$t/"* "$corpus/" 2>/dev/null || true
  log="$build/fuzz-$t.log"
  echo "fuzz: $t for ${seconds}s" >&2
  # -timeout: an input taking longer is a hang; -rss_limit_mb: memory beyond is a finding.
  set +e
  "$program" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
    -print_final_stats=1 -artifact_prefix="$findings/" > "$log" 2>&1
  rc=$?
  set -e
  execs=$(grep -h "stat::number_of_executed_units" "$log" | awk '{s += $2} END {print s + 0}')
  rate=$(grep -h "stat::average_exec_per_sec" "$log" | awk '{s += $2} END {print s + 0}')
  edges=$(grep -ho "cov: [0-9]*" "$log" | tail -1 | awk '{print $2 + 0}')
  crashes=$(find "$findings" -name 'crash-*' | wc -l)
  timeouts=$(find "$findings" -name 'timeout-*' | wc -l)
  ooms=$(find "$findings" -name 'oom-*' -o -name 'leak-*' | wc -l)
  size=$(find "$corpus" -type f | wc -l)
  echo "| $t | $seconds | $execs | $rate | $edges | $size | $crashes | $timeouts | $ooms |" >> "$summary"
  if ((crashes + timeouts + ooms)) || { [ "$rc" -ne 0 ] && ! grep -q "Done [0-9]* runs" "$log"; }; then
    found=1
    echo "fuzz: $t: findings in $findings (log $log)" >&2
  fi
done
cat "$summary"
exit "$found"
