#!/usr/bin/env bash
# One entry point for a fresh Debian machine: installs what is missing
# (apt-get), configures and builds (Release), then runs one job.
#
#   tools/run.sh bench [shadowvol bench options]   the cycle table (main job)
#   tools/run.sh test                              the whole test suite (ctest)
#   tools/run.sh fuzz [SECONDS]                    each libFuzzer target of
#                                                  tests/fuzz for SECONDS (60)
#   tools/run.sh cross                             the core suite for Windows x64
#                                                  under wine64 and for 32-bit x86
#                                                  natively and under qemu-i386
#                                                  (docs/PLATFORMS.md)
#   tools/run.sh lint                              the formatter and the analyser
#                                                  (tools/lint.sh: clang-format
#                                                  --dry-run --Werror, clang-tidy
#                                                  over src/ and bench/); the
#                                                  build is configured, not built
#   tools/run.sh fresh [JOB [ARGS]]                JOB (default: test) in a clean
#                                                  minimal Debian root made with
#                                                  mmdebstrap (tools/fresh_root.sh,
#                                                  docs/TESTING.md); root only, long
#
# BUILD_DIR (default: build) chooses the build directory; FUZZ_BUILD_DIR
# (default: build-fuzz) the fuzz build's (clang, SV_FUZZ=ON, only the fuzz
# targets and the libraries they need); WIN64_BUILD_DIR (build-win64) and
# I686_BUILD_DIR (build-i686) the cross builds' (SV_CORE_ONLY). ccache is
# used when installed.
set -euo pipefail

cd "$(dirname "$0")/.."
job="${1:-}"
[ $# -gt 0 ] && shift
case "$job" in
  bench|test|fuzz|cross|lint|fresh) ;;
  *) echo "usage: tools/run.sh bench [options] | tools/run.sh test | tools/run.sh fuzz [SECONDS] | tools/run.sh cross | tools/run.sh lint | tools/run.sh fresh [JOB [ARGS]]" >&2; exit 2 ;;
esac

# The Debian packages this job needs: tools/packages.txt, the one list
# (each line names the jobs it serves; every job builds, or configures
# (lint), so every job takes build's lines too, except fresh: it builds
# nothing on this machine, the job it runs installs its own packages
# inside the clean root).
packages_for() {
  awk -v job="$1" '!/^#/ && NF >= 2 {
      n = split($2, jobs, ",")
      for (i = 1; i <= n; i++) if ((jobs[i] == "build" && job != "fresh") || jobs[i] == job) { print $1; break }
    }' tools/packages.txt
}
mapfile -t packages < <(packages_for "$job")
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

if [ "$job" = fresh ]; then
  exec tools/fresh_root.sh "$@"
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

if [ "$job" = cross ]; then
  # The core suite (shadowvol_tests: differential, errata, contracts,
  # dispatch, ...) on the platforms that are not the host: Windows x64
  # under wine64 (every test program through cmake/wine-run.sh), 32-bit x86
  # natively (multilib) and under qemu-i386 as a Core Duo and an Atom N270,
  # plus the 32-bit `shadowvol bench` table. Each step's seconds are
  # printed, for the CI's budget.
  # step's status is the command's (not the echo's: without the rc a
  # failing ctest under `|| status=1` read as a pass).
  step() {
    local t0=$SECONDS rc=0
    "$@" || rc=$?
    echo "tools/run.sh cross: $* took $((SECONDS - t0)) s (exit $rc)" >&2
    return $rc
  }
  status=0
  wb="${WIN64_BUILD_DIR:-build-win64}"
  ib="${I686_BUILD_DIR:-build-i686}"
  t_all=$SECONDS
  step cmake -S . -B "$wb" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-mingw-w64.cmake "${launcher[@]}" >/dev/null
  step cmake --build "$wb" --target shadowvol_tests shadowvol_bench_asm_tests >&2
  step ctest --test-dir "$wb" --output-on-failure "$@" || status=1
  step cmake -S . -B "$ib" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-i686.cmake "${launcher[@]}" >/dev/null
  step cmake --build "$ib" --target shadowvol_tests shadowvol_bench_core >&2
  step ctest --test-dir "$ib" --output-on-failure "$@" || status=1
  echo "tools/run.sh cross: $((SECONDS - t_all)) s in all" >&2
  exit $status
fi

build="${BUILD_DIR:-build}"
# compile_commands.json: clang-tidy's (and an editor's) view of the build.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >/dev/null
if [ "$job" = lint ]; then
  # clang-tidy needs the compile commands only: no source includes a
  # generated header, so the configure above is enough.
  exec tools/lint.sh "$build"
fi
cmake --build "$build" >&2

case "$job" in
  bench) exec "$build/shadowvol" bench "$@" ;;
  test)
    # One entry per core at a time (CTEST_PARALLEL_LEVEL overrides): the
    # entries are mostly single-threaded, and the ASan run alone took about
    # ten minutes one at a time on 2 cores. The timed checks have budgets
    # that hold with the other core busy.
    jobs="${CTEST_PARALLEL_LEVEL:-$(nproc)}"
    ctest --test-dir "$build" --output-on-failure --parallel "$jobs" "$@"
    # The same suite once more under AddressSanitizer + UBSan (Debug): it
    # catches undefined behaviour in the C that the differential inputs reach.
    san="${build}-sanitize"
    cmake -S . -B "$san" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DSV_SANITIZE=ON >/dev/null
    cmake --build "$san" >&2
    ctest --test-dir "$san" --output-on-failure --parallel "$jobs" "$@"
    ;;
esac
