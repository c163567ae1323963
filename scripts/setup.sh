#!/usr/bin/env bash
# Installs vbsim's Debian dependencies (only what is missing) and builds it.
# Idempotent: a second run installs nothing and rebuilds only what changed.
#   VBSIM_BUILD_DIR   build directory (default build/)
#   VBSIM_CMAKE_ARGS  extra CMake options for a new build directory
#                     (scripts/test.sh --sanitize, scripts/fuzz.sh set them)
#   VBSIM_FUZZ=1      also install clang and its libFuzzer runtime
#   --suite           also install the packages the workload suite's scenes come from
#                     (scripts/suite.py, traces/suite/scenes.json, docs/suite.md)
#   --open3d          also install Debian's Open3D (python3-open3d, without its recommends),
#                     for the capture test of its RaycastingScene (docs/capture.md, "Open3D")
set -euo pipefail
suite=0
open3d=0
for arg in "$@"; do
  case "$arg" in
    --suite) suite=1 ;;
    --open3d) open3d=1 ;;
    *) echo "usage: scripts/setup.sh [--suite] [--open3d]" >&2; exit 2 ;;
  esac
done
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

# git: the revision `vbsim --version` reports; libssl-dev: SHA-256 of the inputs every
# output records; slurm-wlm and munge: the Slurm backend's test runs a one-node cluster;
# embree-tools: the path tracer `vbsim capture` is tested on; libmpfr-dev: the narrow box
# test (rtcore-systemc's low-precision arithmetic) is checked against MPFR; time: the workload
# suite reads each run's peak memory from /usr/bin/time -v.
packages=(build-essential cmake pkg-config git libsystemc-dev catch2 libfmt-dev nlohmann-json3-dev
          libembree-dev libassimp-dev libcli11-dev libgmp-dev libmpfr-dev libssl-dev libstb-dev
          python3-numpy python3-matplotlib slurm-wlm munge embree-tools time)
if [ "${VBSIM_FUZZ:-0}" = 1 ]; then
  packages+=(clang libclang-rt-dev)
fi
# The suite's meshes: libcgal-demo (CGAL's demo data, /usr/share/doc/libcgal-demo/data.tar.gz:
# armadillo, bunny00, diplodocus, refined_elephant; 24 MB, and libcgal-dev with it) and
# assimp-testmodels (assimp's test models, 74 MB installed). Not in the default set: large.
if [ "$suite" = 1 ]; then
  packages+=(libcgal-demo assimp-testmodels)
fi

# blender: Blender's Cycles renders through the shared libembree3, so `vbsim capture` traces it
# unmodified (scripts/blender_capture.py, docs/capture.md); without its recommended packages.
lean_packages=(blender)
# --open3d: Open3D's Python module and its libraries, without the packages it only
# recommends (large all the same: a few hundred MB with its dependencies).
if [ "$open3d" = 1 ]; then
  lean_packages+=(python3-open3d)
fi

missing_of() {
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
  done
}
mapfile -t missing < <(missing_of "${packages[@]}")
mapfile -t missing_lean < <(missing_of "${lean_packages[@]}")
if ((${#missing[@]} + ${#missing_lean[@]})); then
  echo "vbsim setup: installing ${missing[*]} ${missing_lean[*]}" >&2
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  if ((${#missing[@]})); then
    DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq "${missing[@]}" >&2
  fi
  if ((${#missing_lean[@]})); then
    DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
      "${missing_lean[@]}" >&2
  fi
fi

build="${VBSIM_BUILD_DIR:-$root/build}"
mkdir -p "$build"
log="$build/setup-configure.log"
# Build quietly; show the log only when something fails.
if [ ! -f "$build/CMakeCache.txt" ]; then
  echo "vbsim setup: configuring and building in $build (first run takes a few minutes)" >&2
  # shellcheck disable=SC2086  # VBSIM_CMAKE_ARGS is a list of options
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release ${VBSIM_CMAKE_ARGS:-} > "$log" 2>&1 || { cat "$log" >&2; exit 1; }
fi
blog="$build/setup-build.log"
cmake --build "$build" -j "$(nproc)" > "$blog" 2>&1 || { cat "$blog" >&2; exit 1; }
