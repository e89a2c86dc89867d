#!/usr/bin/env bash
# One entry point for a fresh Debian machine: installs what is missing
# (apt-get), configures and builds (Release), then runs one job.
#
#   tools/run.sh bench [shadowvol bench options]   the cycle table (main job)
#   tools/run.sh test                              the whole test suite (ctest)
#
# BUILD_DIR (default: build) chooses the build directory.
set -euo pipefail

cd "$(dirname "$0")/.."
job="${1:-}"
[ $# -gt 0 ] && shift
case "$job" in
  bench|test) ;;
  *) echo "usage: tools/run.sh bench [options] | tools/run.sh test" >&2; exit 2 ;;
esac

# Debian packages the build and the tests need.
# libtinygltf-dev builds from its header with nlohmann-json3-dev (and
# libstb-dev, named by its Debian notes); assimp-testmodels gives the loader
# tests third-party malformed glTF files; qemu-user runs the test suite as
# CPUs without AVX-512 and without AVX; libosmesa6-dev gives the Mesa judge
# (src/gljudge) its off-screen llvmpipe GL context; libtbb-dev (oneTBB) runs a
# frame's jobs and screen bands in parallel.
packages=(nasm cmake ninja-build g++ libgtest-dev libbenchmark-dev binutils git
          libtinygltf-dev nlohmann-json3-dev libstb-dev assimp-testmodels qemu-user
          libosmesa6-dev libtbb-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "tools/run.sh: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

build="${BUILD_DIR:-build}"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" >&2

case "$job" in
  bench) exec "$build/shadowvol" bench "$@" ;;
  test)
    ctest --test-dir "$build" --output-on-failure "$@"
    # The same suite once more under AddressSanitizer + UBSan (Debug): it
    # catches undefined behaviour in the C that the differential inputs reach.
    san="${build}-sanitize"
    cmake -S . -B "$san" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DSV_SANITIZE=ON >/dev/null
    cmake --build "$san" >&2
    ctest --test-dir "$san" --output-on-failure "$@"
    ;;
esac
