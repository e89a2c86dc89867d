#!/usr/bin/env bash
# One entry point for a fresh Debian machine: installs what is missing
# (apt-get), configures and builds (Release), then runs one job.
#
#   tools/run.sh bench [shadowvol bench options]   the cycle table (main job)
#   tools/run.sh test                              the whole test suite (ctest)
#   tools/run.sh fuzz [SECONDS]                    each libFuzzer target of
#                                                  tests/fuzz for SECONDS (60)
#
# BUILD_DIR (default: build) chooses the build directory; FUZZ_BUILD_DIR
# (default: build-fuzz) the fuzz build's (clang, SV_FUZZ=ON, only the fuzz
# targets and the libraries they need). ccache is used when installed.
set -euo pipefail

cd "$(dirname "$0")/.."
job="${1:-}"
[ $# -gt 0 ] && shift
case "$job" in
  bench|test|fuzz) ;;
  *) echo "usage: tools/run.sh bench [options] | tools/run.sh test | tools/run.sh fuzz [SECONDS]" >&2; exit 2 ;;
esac

# Debian packages the build and the tests need.
# libtinygltf-dev builds from its header with nlohmann-json3-dev (and
# libstb-dev, named by its Debian notes); assimp-testmodels gives the loader
# tests third-party malformed glTF files; qemu-user runs the test suite as
# CPUs without AVX-512 and without AVX; libosmesa6-dev gives the Mesa judge
# (src/gljudge) its off-screen llvmpipe GL context; libtbb-dev (oneTBB) runs a
# frame's jobs and screen bands in parallel; clang and libclang-rt-dev
# (libFuzzer) build the fuzz targets (tests/fuzz: the test and fuzz jobs).
packages=(nasm cmake ninja-build g++ libgtest-dev libbenchmark-dev binutils git
          libtinygltf-dev nlohmann-json3-dev libstb-dev assimp-testmodels qemu-user
          libosmesa6-dev libtbb-dev)
[ "$job" = bench ] || packages+=(clang libclang-rt-dev)
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

launcher=()
if command -v ccache >/dev/null 2>&1; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi

if [ "$job" = fuzz ]; then
  # libFuzzer targets (tests/fuzz): GLB bytes, .gltf JSON (with a glTF key
  # dictionary), the *_checked entry points against c_ref, GLB bytes
  # through the animated scene (poses, skinning, planes), and the render and
  # scene command lines (fuzz_options). The seed corpus
  # is generated (sv_fuzz_corpus); ../shared/models and Debian's
  # assimp-testmodels seed it too when present (copied into the work
  # corpus under the build folder, never into the repository). A finding
  # (crash, sanitizer report, FUZZ FINDING) stops with status 1 and leaves
  # the input in $fb/fuzz-artifacts/.
  secs="${1:-60}"
  case "$secs" in ''|*[!0-9]*) echo "tools/run.sh fuzz: SECONDS must be a whole number" >&2; exit 2 ;; esac
  fb="${FUZZ_BUILD_DIR:-build-fuzz}"
  CC=clang CXX=clang++ cmake -S . -B "$fb" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSV_FUZZ=ON -DSV_BUILD_TESTS=OFF "${launcher[@]}" >/dev/null
  cmake --build "$fb" --target fuzz_glb fuzz_gltf_json fuzz_checked fuzz_scene fuzz_options sv_fuzz_corpus >&2
  corpus="$fb/fuzz-corpus"
  mkdir -p "$corpus/seed" "$fb/fuzz-artifacts"
  "$fb/tests/fuzz/sv_fuzz_corpus" "$corpus/seed" models/character_1344.glb
  for d in ../shared/models /usr/share/assimp/models/glTF2; do
    [ -d "$d" ] || continue
    find "$d" -name '*.glb' -size -300k -exec cp -n {} "$corpus/seed/glb/" \; 2>/dev/null || true
    find "$d" -name '*.gltf' -size -300k -exec cp -n {} "$corpus/seed/gltf/" \; 2>/dev/null || true
  done
  status=0
  for t in fuzz_glb fuzz_gltf_json fuzz_checked fuzz_scene fuzz_options; do
    work="$corpus/$t"; mkdir -p "$work"
    args=(-max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -max_len=131072 -print_final_stats=1
          -artifact_prefix="$fb/fuzz-artifacts/$t-")
    seeds=()
    case $t in
      fuzz_glb|fuzz_scene) seeds=("$corpus/seed/glb") ;;
      fuzz_gltf_json) seeds=("$corpus/seed/gltf"); args+=(-dict=tests/fuzz/gltf.dict) ;;
      fuzz_options) seeds=("$corpus/seed/options") ;;
    esac
    log="$fb/fuzz-$t.log"
    echo "tools/run.sh fuzz: $t for $secs s (log: $log)" >&2
    if "$fb/tests/fuzz/$t" "${args[@]}" "$work" "${seeds[@]}" >"$log" 2>&1; then
      execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
      rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
      cov=$( (grep -E '^#[0-9]+[[:space:]]+DONE' "$log" || true) | sed -n 's/.*cov: \([0-9]*\) ft: \([0-9]*\).*/\1 edges, \2 features/p')
      echo "$t: ${execs:-?} executions in $secs s (${rate:-?}/s), coverage ${cov:-?}, corpus $(ls "$work" | wc -l) inputs, no finding"
    else
      echo "$t: FINDING (see $log and $fb/fuzz-artifacts/)" >&2
      grep -E 'FUZZ FINDING|ERROR: |SUMMARY: ' "$log" | head -5 >&2
      status=1
    fi
  done
  exit $status
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
