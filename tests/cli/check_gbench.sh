#!/usr/bin/env bash
# shadowvol_gbench as a user runs it: a couple of routines under a tiny
# --benchmark_min_time print their rows (both regimes, every variant this CPU
# runs, the counters), none fails its check against c_ref, the JSON output
# names the cases and the counters, and bad arguments exit 2 (3 for a model
# that cannot be loaded). No timing is checked.
# usage: check_gbench.sh PATH/TO/shadowvol_gbench
set -u
gb="$1"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Google Benchmark 1.7 (Debian bookworm) takes the minimum time as a plain
# number of seconds (1.8 added the "0.01s" / "100x" forms).
min_time=--benchmark_min_time=0.01

"$gb" $min_time --benchmark_filter='^(count_facing|create_shadow_volume)/' \
  >"$tmp/out" 2>"$tmp/err"; rc=$?
[ $rc -eq 0 ] || err "exited $rc: $(head -c 600 "$tmp/err")"
row='^(count_facing|create_shadow_volume)/[a-z0-9_]+/(moving|fixed) +[0-9.]+ (ns|us|ms|s) '
rows=$(grep -cE "$row" "$tmp/out")
# 2 routines x (c_ref, c_branchless, sse2_paper at least) x 2 regimes
[ "$rows" -ge 12 ] || err "expected at least 12 rows, got $rows: $(cat "$tmp/out")"
counted=$(grep -E "$row" "$tmp/out" | grep -E 'elements_per_second=[0-9.]+[kMGT]?/s' |
          grep -cE 'ticks_per_element=[0-9.]+')
[ "$counted" -eq "$rows" ] || err "$((rows - counted)) rows lack the counters"
for name in count_facing/c_ref/moving count_facing/c_ref/fixed \
            create_shadow_volume/sse2_paper/moving create_shadow_volume/c_branchless/fixed; do
  grep -qE "^$name " "$tmp/out" || err "no row $name"
done
grep -qE '^(count_facing_cull|create_sil_triangles)/' "$tmp/out" && err "the filter let other routines run"
grep -q 'ERROR OCCURRED' "$tmp/out" && err "a case failed: $(grep 'ERROR OCCURRED' "$tmp/out")"
grep -q 'shadowvol_mesh: 1344 triangles' "$tmp/out" "$tmp/err" || err "the context does not name the mesh"

"$gb" $min_time --benchmark_filter='^create_sil_triangles/c_ref/' --benchmark_format=json \
  >"$tmp/json" 2>"$tmp/err"; rc=$?
[ $rc -eq 0 ] || err "--benchmark_format=json exited $rc: $(head -c 600 "$tmp/err")"
for field in '"name": "create_sil_triangles/c_ref/moving"' '"name": "create_sil_triangles/c_ref/fixed"' \
             '"ticks_per_element": [0-9]' '"elements_per_second": [0-9]' '"shadowvol_tsc_hz": "[0-9]+"' \
             '"label": "2016 SilEdges"'; do
  grep -qE "$field" "$tmp/json" || err "JSON without $field"
done

expect_status() { # expected-status description args...
  local want=$1; shift; local what=$1; shift
  "$gb" "$@" >"$tmp/out" 2>"$tmp/err"; local got=$?
  [ $got -eq "$want" ] || err "$what: exit $got, want $want ($(head -c 300 "$tmp/err"))"
  if [ "$want" -ne 0 ]; then
    [ -s "$tmp/err" ] || err "$what: no message on stderr"
  fi
}
expect_status 0 "--help" --help
grep -q -- '--model FILE' "$tmp/out" || err "--help does not describe --model"
expect_status 2 "unknown flag" --no-such-flag
expect_status 2 "--seed abc" --seed abc
expect_status 2 "--model without a value" --model
expect_status 3 "--model missing file" --model "$tmp/no_such_model.glb"

[ $fail -eq 0 ] && echo "shadowvol_gbench: $rows rows, counters and JSON present, every case checked"
exit $fail
