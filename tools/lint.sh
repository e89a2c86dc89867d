#!/usr/bin/env bash
# The formatter and the analyser (docs/TESTING.md, "The formatter and the
# analyser"). Each prints its seconds.
#
#   tools/lint.sh format          clang-format --dry-run --Werror over the
#                                 tracked C/C++ files (.clang-format): exit 1
#                                 when one is not formatted
#   tools/lint.sh format --fix    format them in place
#   tools/lint.sh tidy [BUILD]    clang-tidy (.clang-tidy) over src/ and
#                                 bench/ through run-clang-tidy -j2, with
#                                 BUILD's compile_commands.json (default:
#                                 $BUILD_DIR or build; configured, not
#                                 built, when it has none): exit 1 on any
#                                 finding
#   tools/lint.sh [BUILD]         both (tools/run.sh lint)
#
# LINT_JOBS (default 2) sets run-clang-tidy's -j. The packages: tools/
# packages.txt, job lint (clang-format, clang-tidy).
set -euo pipefail

cd "$(dirname "$0")/.."
root="$(pwd -P)"

lint_format() {
  local fix="${1:-}" t0=$SECONDS files
  mapfile -t files < <(git ls-files -- '*.c' '*.cpp' '*.h')
  if [ ${#files[@]} -eq 0 ]; then
    echo "tools/lint.sh format: no tracked C/C++ file (not a git checkout?)" >&2
    return 2
  fi
  local version
  version="$(clang-format --version)"
  if [ "$fix" = --fix ]; then
    clang-format -i "${files[@]}"
    echo "tools/lint.sh format --fix: ${#files[@]} files formatted ($version), $((SECONDS - t0)) s" >&2
    return 0
  fi
  local log rc=0 bad
  log="$(mktemp)"
  clang-format --dry-run --Werror "${files[@]}" >"$log" 2>&1 || rc=$?
  # One line per file that would change (clang-format prints each place).
  bad=$( (grep -oE '^[^:[:space:]]+\.(c|cpp|h):[0-9]+:[0-9]+: error' "$log" || true) | cut -d: -f1 | sort -u)
  if [ $rc -ne 0 ]; then
    head -40 "$log" >&2
    echo "tools/lint.sh format: $(printf '%s' "$bad" | grep -c . || true) of ${#files[@]} files are not formatted ($version):" >&2
    printf '  %s\n' $bad >&2
    echo "tools/lint.sh format: fix them with tools/lint.sh format --fix; $((SECONDS - t0)) s" >&2
    rm -f "$log"
    return 1
  fi
  rm -f "$log"
  echo "tools/lint.sh format: ${#files[@]} files formatted ($version), $((SECONDS - t0)) s" >&2
}

lint_tidy() {
  local build="${1:-${BUILD_DIR:-build}}" t0=$SECONDS
  if [ ! -f "$build/compile_commands.json" ]; then
    # Configuring is enough (no source includes a generated header): an
    # existing build keeps its settings and gains the database.
    echo "tools/lint.sh tidy: configuring $build for its compile_commands.json" >&2
    if [ -f "$build/CMakeCache.txt" ]; then
      cmake -B "$build" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >/dev/null
    else
      cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >/dev/null
    fi
  fi
  local t_cfg=$((SECONDS - t0))
  # The checks, and the extra argument GCC's flags need, are .clang-tidy's;
  # the header filter is its own, anchored at this checkout.
  local re_root log rc=0
  re_root="$(printf '%s' "$root" | sed 's/[][\.*^$+?(){}|]/\\&/g')"
  log="$build/clang-tidy.log"
  run-clang-tidy -j "${LINT_JOBS:-2}" -p "$build" -quiet \
    -header-filter="^$re_root/(src|bench|include)/" \
    "^$re_root/(src|bench)/.*\.(c|cpp)\$" >"$log.raw" 2>&1 || rc=$?
  sed 's/\x1b\[[0-9;]*m//g' "$log.raw" >"$log" && rm -f "$log.raw"
  local files findings n
  files=$(grep -c '^clang-tidy' "$log" || true)
  # A header's finding is printed once per file that includes it: once here.
  findings=$( (grep -E '^/[^:]+:[0-9]+:[0-9]+: (warning|error): .*\]$' "$log" || true) \
    | sed "s|^$root/||" | sort -u)
  n=$(printf '%s' "$findings" | grep -c . || true)
  if [ "$n" -gt 0 ] || [ "$rc" -ne 0 ]; then
    [ -n "$findings" ] && printf '%s\n' "$findings" >&2
    echo "tools/lint.sh tidy: $files files, $n findings (run-clang-tidy exit $rc; the whole output: $log), $((SECONDS - t0)) s" >&2
    return 1
  fi
  echo "tools/lint.sh tidy: $files files, no finding ($(clang-tidy --version | sed -n 's/.*LLVM version \([0-9.]*\).*/clang-tidy \1/p')), $((SECONDS - t0)) s (configure $t_cfg s)" >&2
}

case "${1:-}" in
  format) shift; lint_format "$@" ;;
  tidy) shift; lint_tidy "$@" ;;
  -h|--help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  -*) echo "usage: tools/lint.sh [format [--fix] | tidy [BUILD_DIR] | BUILD_DIR]" >&2; exit 2 ;;
  *)
    status=0
    lint_format || status=1
    lint_tidy "$@" || status=1
    exit $status
    ;;
esac
