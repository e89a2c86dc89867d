#!/usr/bin/env bash
# tools/instruction_counts.sh: a row per kernel the bench ran, counts that
# are whole and positive, and with a --limits result the cycles and IPC
# computed from it (here a made-up result: 2 core cycles per tick, 1 tick
# per element, so cycles per element 2.00 and IPC half the count).
# usage: check_instruction_counts.sh PATH/TO/shadowvol SOURCE_DIR
set -u
sv="$1"; src="$2"
command -v valgrind >/dev/null || { echo "SKIP: no valgrind"; exit 77; }
command -v python3 >/dev/null || { echo "SKIP: no python3 (the tool reads --json with it)"; exit 77; }
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cat >"$tmp/r.json" <<'J'
{"schema": "shadowvol-bench/1", "limits": {"core_cycles_per_tick": 2.0},
 "results": [{"model": "character_1344.glb", "routine": "create_sil_triangles", "variant": "c_ref",
              "regime": "moving", "ticks_per_element_median": 1.0, "checked": true}]}
J
"$src/tools/instruction_counts.sh" --json "$tmp/r.json" "$sv" >"$tmp/out" 2>"$tmp/err" \
  || { cat "$tmp/err"; echo "FAIL: the tool failed"; exit 1; }
cat "$tmp/out"
for r in calculate_facing calculate_cull_bits count_facing count_facing_cull create_sil_triangles create_cap_triangles; do
  grep -q "^$r  *c_ref " "$tmp/out" || err "no c_ref row for $r"
done
grep -q "^create_sil_triangles  *sse2_paper " "$tmp/out" || err "no row for the asm port"
awk '$1 ~ /^(calc|count|create)/ { if (!($3 > 0) || !($4 > 0) || !($5 > 0)) { print "bad counts: " $0; bad = 1 } }
     END { exit bad }' "$tmp/out" || err "a count is not positive"
awk '$1 == "create_sil_triangles" && $2 == "c_ref" {
       if ($6 != "2.00") { print "cycles " $6; bad = 1 }
       d = $5 / 2 - $7; if (d < 0) d = -d; if (d > 0.006) { print "IPC " $7 " vs " $5 / 2; bad = 1 }
       seen = 1 }
     END { exit bad || !seen }' "$tmp/out" || err "cycles or IPC not computed from the result"
"$src/tools/instruction_counts.sh" --json "$tmp/missing.json" "$sv" >/dev/null 2>&1; [ $? -eq 2 ] || err "a missing result did not exit 2"
[ $fail -eq 0 ] && echo "check_instruction_counts: ok"
exit $fail
