#!/usr/bin/env bash
# Installs and builds vbsim if needed, then runs the whole test suite through ctest.
#   scripts/test.sh [CTEST_ARGS...]             the suite, build/
#   scripts/test.sh --sanitize [CTEST_ARGS...]  the same suite built with AddressSanitizer and
#       UndefinedBehaviorSanitizer in build-sanitize/: any report aborts the test that made it
#       (docs/reliability.md)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
sanitize=0
args=()
for a in "$@"; do
  if [ "$a" = --sanitize ]; then sanitize=1; else args+=("$a"); fi
done
if ((sanitize)); then
  export VBSIM_BUILD_DIR="${VBSIM_SANITIZE_BUILD_DIR:-$root/build-sanitize}"
  export VBSIM_CMAKE_ARGS="-DVBSIM_SANITIZE=ON"
  # Leaks are not errors: SystemC, Embree and assimp keep process-lifetime allocations.
  export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0:abort_on_error=1:strict_string_checks=1:check_initialization_order=1}"
  export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
fi
"$root/scripts/setup.sh"
cd "${VBSIM_BUILD_DIR:-$root/build}"
ctest --output-on-failure -j "$(nproc)" "${args[@]}"
