#!/usr/bin/env bash
# `shadowvol bench --report` (issues 15 and 17): one routine of a result,
# one routine across several results (a row per CPU), and the planner's
# choices of a result that records its plans; bad arguments exit 2, a
# result without the routine exits 3.
# usage: check_report_cli.sh PATH/TO/shadowvol SOURCE_DIR
set -u
sv="$1"; src="$2"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
res="$src/docs/results"

# A bench result with pipeline rows, and one written before them.
with=$(grep -l '"routine": *"pipeline"' "$res"/*.json | grep -v scaling | head -1)
without=$(grep -L '"routine": *"pipeline"' "$res"/*.json | grep -v scaling | head -1)
[ -n "$with" ] && [ -n "$without" ] || { echo "FAIL: docs/results lacks the two kinds of result"; exit 1; }

"$sv" bench --report "$with" --routine pipeline >"$tmp/one" 2>"$tmp/err" || err "--report --routine: $(cat "$tmp/err")"
[ "$(grep -c '^| `' "$tmp/one")" -eq 1 ] || err "--routine pipeline printed other routines: $(cat "$tmp/one")"
grep -q '^| `pipeline` |' "$tmp/one" || err "no pipeline row"

"$sv" bench --report "$with" "$without" --routine pipeline >"$tmp/many" 2>"$tmp/err" || err "several files: $(cat "$tmp/err")"
[ "$(grep -c '^| .*TSC' "$tmp/many")" -eq 1 ] || err "not one row per file with pipeline rows"
grep -q "No \`pipeline\` rows .*$(basename "$without")" "$tmp/many" || err "the file without the rows is not named"
# best vs sse2_paper is sse2_paper's median over the smallest of the row.
awk -F'|' 'NR == 1 { for (i = 1; i <= NF; i++) { gsub(/ /, "", $i); col[$i] = i } next }
           /TSC/ { best = 1e9; for (i = 5; i < col["bestvssse2_paper"]; i++) { v = $i + 0; if (v > 0 && v < best) best = v }
                   p = $(col["sse2_paper"]) + 0; r = $(col["bestvssse2_paper"]); sub(/x/, "", r)
                   d = p / best - r; if (d < 0) d = -d; if (d > 0.006) { print "ratio " r " vs " p / best; bad = 1 } }
           END { exit bad }' <(grep '^| CPU\|TSC' "$tmp/many") || err "best vs sse2_paper is not sse2_paper / best"

# The planner's choices of a document with "plans".
cat >"$tmp/plans.json" <<'J'
{"schema": "shadowvol-bench/1", "cpu": {"model": "Test CPU", "tsc_hz": 2e9, "isa": ["sse2", "avx2"],
                                        "model_key": "AuthenticAMD 25/1/1 avx2 Test CPU"},
 "commit": "abc1234", "timer": "rdtscp", "compiler": "gcc",
 "results": [{"model": "m.glb", "triangles": 1344, "routine": "pipeline", "variant": "c_ref",
              "regime": "moving", "ticks_per_element_median": 6.0, "checked": true},
             {"model": "m.glb", "triangles": 1344, "routine": "pipeline", "variant": "planned",
              "regime": "moving", "ticks_per_element_median": 2.0, "checked": true}],
 "plans": [{"model": "m.glb", "triangles": 1344, "size_class": 0, "class_triangles": 1344,
            "source": "measured", "variants": {"calculate_facing": "avx2", "create_cap_triangles": "sse2_paper"}}]}
J
"$sv" bench --report "$tmp/plans.json" >"$tmp/plans" 2>"$tmp/err" || err "--report of a plan: $(cat "$tmp/err")"
grep -q '^| size class | measured on | meshes (triangles) | source | calculate_facing | create_cap_triangles |$' "$tmp/plans" \
  || err "no planner's-choices header: $(cat "$tmp/plans")"
grep -q '^| 0 | 1344 | 1344 | measured | avx2 | sse2_paper |$' "$tmp/plans" || err "no planner's-choices row"
grep -q '^| `pipeline` | 6.00 | 2.00 | 3.0x |$' "$tmp/plans" || err "the pipeline row is wrong: $(cat "$tmp/plans")"

# The family and model from cpu.model_key, where a result has it.
"$sv" bench --report "$tmp/plans.json" "$with" --routine pipeline >"$tmp/fam" 2>"$tmp/err" || err "several with a key: $(cat "$tmp/err")"
grep -q '^| Test CPU (family 25 model 1), TSC 2.00 GHz | AVX2 | abc1234 |' "$tmp/fam" || err "no family in the CPU column: $(cat "$tmp/fam")"

# Bad use.
"$sv" bench --report "$with" "$without" >/dev/null 2>&1; [ $? -eq 2 ] || err "several files without --routine did not exit 2"
"$sv" bench --report "$with" --routine no_such_routine >/dev/null 2>"$tmp/err"; rc=$?
[ $rc -eq 3 ] || err "an absent routine exited $rc, not 3"
grep -q "no rows of no_such_routine" "$tmp/err" || err "an absent routine: no message"
"$sv" bench --compare "$with" --routine pipeline >/dev/null 2>&1; [ $? -eq 2 ] || err "--compare took --routine"

[ $fail -eq 0 ] && echo "check_report_cli: ok"
exit $fail
