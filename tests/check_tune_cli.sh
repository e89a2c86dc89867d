#!/usr/bin/env bash
# `shadowvol tune` (issue 15): measures a class, prints a timing per
# routine and variant with the planned one marked, saves this CPU's
# section of the wisdom file; bad arguments exit 2, an unwritable or
# foreign file exits 3 and is left as it was.
# usage: check_tune_cli.sh PATH/TO/shadowvol
set -u
sv="$1"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$sv" tune --class 0 --wisdom "$tmp/w/wisdom" >"$tmp/out" 2>"$tmp/err"
rc=$?
cat "$tmp/out"
[ $rc -eq 0 ] || err "tune --class 0 exited $rc: $(cat "$tmp/err")"
[ "$(grep -c '<- planned' "$tmp/out")" -eq 6 ] || err "not one planned variant per routine"
for r in calculate_facing calculate_cull_bits count_facing count_facing_cull create_sil_triangles \
         create_cap_triangles; do
  grep -q "^$r .* c_ref " "$tmp/out" || err "no c_ref timing for $r"
  [ "$(grep -c "^class 0 $r " "$tmp/w/wisdom")" -eq 1 ] || err "the wisdom has no single class-0 line for $r"
done
[ "$(head -1 "$tmp/w/wisdom")" = "shadowvol-wisdom 1" ] || err "the wisdom file has no header"
cpu=$(sed -n 's/^cpu  *//p' "$tmp/out")
grep -qxF "cpu $cpu" "$tmp/w/wisdom" || err "the wisdom is not keyed by this CPU ($cpu)"
# The planned variant of each routine is the fastest printed for it, or the
# static choice within 3% of the fastest (the planner's margin against
# noise, src/plan/planner.cpp); a variant that displaced the static choice
# beat it by more than the margin.
awk '$1 ~ /^(calc|count|create)/ { if (!($1 in best) || $3 < best[$1]) best[$1] = $3 }
     /<- planned/ { planned[$1] = $3; pstatic[$1] = /static/ }
     /\(static\)|planned, static/ { stat[$1] = $3 }
     END { for (r in best) {
             if (planned[r] == best[r] && (pstatic[r] || stat[r] > best[r] * 1.03)) continue
             if (pstatic[r] && planned[r] <= best[r] * 1.03) continue
             print r; bad = 1 }
           exit bad }' "$tmp/out" \
  || err "a planned variant is neither the fastest nor the static choice within 3% of it"

# --dry-run saves nothing.
"$sv" tune --class 0 --dry-run --wisdom "$tmp/dry" >/dev/null 2>&1 || err "--dry-run failed"
[ ! -e "$tmp/dry" ] || err "--dry-run wrote the wisdom file"

# expect STATUS ARGS...
expect() {
  local want=$1; shift
  "$sv" tune "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  [ $rc -eq "$want" ] || err "tune $* exited $rc, expected $want"
  [ -s "$tmp/err" ] || err "tune $* printed no message"
}
expect 2 --class 9
expect 2 --class
expect 2 --sideways
expect 2 --wisdom ""
printf 'my notes, not wisdom\n' >"$tmp/notes"
expect 3 --class 0 --wisdom "$tmp/notes"
[ "$(cat "$tmp/notes")" = "my notes, not wisdom" ] || err "tune overwrote a file that is not a wisdom file"
: >"$tmp/blocker"
expect 3 --class 0 --wisdom "$tmp/blocker/wisdom"
exit $fail
