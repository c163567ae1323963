#!/usr/bin/env bash
# Installs and builds vbsim if needed, then runs the whole test suite through ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
cd "${VBSIM_BUILD_DIR:-$root/build}"
ctest --output-on-failure -j "$(nproc)" "$@"
