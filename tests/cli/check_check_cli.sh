#!/usr/bin/env bash
# `shadowvol check` (issue 16): exit 0 and one line per routine and variant
# this CPU runs (the count from the variant list that --help prints and the
# routines each variant has); the seed replays the same output; under
# SV_ISA=avx2 the AVX-512 variants are skipped with the reason (where the
# build has them); "planned" is a wisdom file's plan where there is one; --variant / --function narrow the lines; --bench adds
# ticks per call; bad arguments exit 2 naming what is known.
# usage: check_check_cli.sh PATH/TO/shadowvol [SECONDS]
#   SECONDS: the most a full check may take (default 10)
set -u
sv="$1"
budget="${2:-10}"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

start=$(date +%s)
"$sv" check --seed 42 >"$tmp/a" 2>"$tmp/err"
rc=$?
took=$(( $(date +%s) - start ))
cat "$tmp/a"
[ $rc -eq 0 ] || err "check exited $rc: $(cat "$tmp/err")"
[ "$took" -le "$budget" ] || err "check took $took s (at most $budget s allowed)"
grep -q '^seed      42 ' "$tmp/a" || err "the seed line does not name seed 42"

routines="calculate_facing calculate_cull_bits calculate_facing_count count_facing count_facing_cull
          create_sil_triangles create_cap_triangles shadow_volume shadow_volume_cull
          shadow_volume_for_light derive_planes facing_from_positions skinning skin_planes
          extrude derive_planes_clustered"
variants=$("$sv" check --help | sed -n '/^  --variant V/{n;p}')
[ -n "$variants" ] || err "--help lists no variants"
# One line per routine and variant that has it: every variant has C-F and
# the volume except the facing-only ones; every line ok here but those of
# variants this CPU lacks or SV_ISA holds back (skipped, with that reason),
# no line twice.
lines=$(grep -cE '^(calc|count|create|shadow|derive|facing|skin|extrude)' "$tmp/a")
skips=$(grep -cE '^(calc|count|create|shadow|derive|facing|skin|extrude)[a-z_]* +[a-z0-9_]+ +skipped \((this CPU lacks [a-z0-9 ]+|SV_ISA=[a-z0-9]+ holds dispatch at [a-z0-9]+)\)$' "$tmp/a")
for r in $routines; do
  for v in $variants; do
    n=$(grep -cE "^$r +$v +ok \([0-9]+ cases\)$" "$tmp/a")
    [ "$n" -le 1 ] || err "$r $v printed $n times"
  done
done
for v in $variants; do
  grep -qE "^[a-z_]+ +$v +(ok |skipped \()" "$tmp/a" || err "no line for variant $v"
done
for r in $routines; do
  [ $r = shadow_volume_for_light ] || grep -qE "^$r +c_ref +ok " "$tmp/a" || err "no ok line for $r c_ref"
  # planned runs a one-pass or clustered kernel only where the planner chose one.
  [ $r = skin_planes ] || [ $r = derive_planes_clustered ] || grep -qE "^$r +planned +ok " "$tmp/a" \
    || err "no ok line for $r planned"
done

# The kernels' routines (C-F and the volume) have the same variants, and
# so have the facing routines (A, B): a line missing from one shows.
set_of() { grep -E "^$1 " "$tmp/a" | awk '{print $2}' | tr '\n' ' '; }
for r in count_facing_cull create_sil_triangles create_cap_triangles shadow_volume shadow_volume_cull; do
  [ "$(set_of $r)" = "$(set_of count_facing)" ] || err "$r's variants ($(set_of $r)) are not count_facing's"
done
for r in calculate_cull_bits calculate_facing_count; do
  [ "$(set_of $r)" = "$(set_of calculate_facing)" ] || err "$r's variants are not calculate_facing's"
done
# The deforming surfaces' planes and facing from positions: one table.
[ "$(set_of derive_planes)" = "$(set_of facing_from_positions)" ] \
  || err "derive_planes' variants are not facing_from_positions'"
# Seed 002's program: its own table (c_ref, avx2, avx512) and planned.
[ "$(set_of extrude)" = "c_ref avx2 avx512 planned " ] \
  || err "extrude's variants ($(set_of extrude)) are not c_ref avx2 avx512 planned"
# The planes by clusters: their own table (c_ref, avx512), and planned
# where the planner chose clusters.
case "$(set_of derive_planes_clustered)" in
  "c_ref avx512 "|"c_ref avx512 planned ") ;;
  *) err "derive_planes_clustered's variants ($(set_of derive_planes_clustered)) are not c_ref avx512 [planned]" ;;
esac
# The per-light call takes a plan: planned only.
[ "$(set_of shadow_volume_for_light)" = "planned " ] || err "shadow_volume_for_light is not planned's alone"
oks=$(grep -cE '^[a-z_]+ +[a-z0-9_]+ +ok \(' "$tmp/a")
[ "$oks" -eq $((lines - skips)) ] || err "$lines lines, $skips skipped, but $oks ok"
grep -qE "^summary   $oks ok, 0 failed, $skips skipped$" "$tmp/a" || err "the summary does not count $oks ok and $skips skipped"

grep -qE '^planned   class 0 (built-in|wisdom), class 1 ' "$tmp/a" || err "no planned line"
# With a wisdom file for this CPU (shadowvol tune), "planned" is its plan.
if "$sv" tune --class 0 --no-stencil --wisdom "$tmp/wisdom" >/dev/null 2>&1; then
  SV_WISDOM="$tmp/wisdom" "$sv" check --seed 42 --variant planned >"$tmp/w" 2>&1 || err "check of the wisdom's plans failed"
  grep -qE '^planned   class 0 wisdom, ' "$tmp/w" || err "the wisdom's plan for class 0 is not the one checked: $(grep '^planned' "$tmp/w")"
else
  err "shadowvol tune --class 0 failed"
fi

# The same seed, the same output.
"$sv" check --seed 42 >"$tmp/b" 2>&1
cmp -s "$tmp/a" "$tmp/b" || err "the same seed gave another output: $(diff "$tmp/a" "$tmp/b" | head -5)"
# No seed: one from the clock, printed.
"$sv" check --function count_facing >"$tmp/c" 2>&1 || err "check without --seed failed"
grep -qE '^seed      [0-9]+ \(replay: --seed [0-9]+\)$' "$tmp/c" || err "no seed printed without --seed"

# Held at avx2: the AVX-512 variants skipped with the reason, the rest ok.
if grep -qE '^count_facing +avx512 +ok ' "$tmp/a"; then
  SV_ISA=avx2 "$sv" check --seed 42 >"$tmp/d" 2>&1 || err "SV_ISA=avx2 check exited $?"
  grep -qE '^count_facing +avx512 +skipped \(SV_ISA=avx2 holds dispatch at avx2\)$' "$tmp/d" \
    || err "avx512 not skipped with its reason under SV_ISA=avx2"
  grep -qE '^count_facing +avx512vbmi +skipped ' "$tmp/d" || err "avx512vbmi not skipped under SV_ISA=avx2"
  grep -qE '^count_facing +avx2 +ok ' "$tmp/d" || err "avx2 not ok under SV_ISA=avx2"
  grep -qE '^summary   [0-9]+ ok, 0 failed, [1-9][0-9]* skipped$' "$tmp/d" || err "no skips counted under SV_ISA=avx2"
fi

# Narrowed: one line.
"$sv" check --seed 5 --variant c_ref --function count_facing_cull >"$tmp/e" 2>&1 || err "narrowed check failed"
[ "$(grep -cE '^(calc|count|create|shadow)' "$tmp/e")" -eq 1 ] || err "--variant --function printed not one line"
grep -qE '^count_facing_cull +c_ref +ok ' "$tmp/e" || err "the narrowed line is not count_facing_cull c_ref"

# A name given twice: one line.
"$sv" check --seed 5 --variant c_ref --variant c_ref --function count_facing --function count_facing >"$tmp/g" 2>&1 \
  || err "check with names given twice failed"
[ "$(grep -cE '^count_facing ' "$tmp/g")" -eq 1 ] || err "a name given twice printed its line twice"

# --bench: ticks and the ratio to c_ref on each line, c_ref at 1.00x.
"$sv" check --seed 5 --function count_facing --bench >"$tmp/f" 2>&1 || err "--bench failed"
grep -qE '^count_facing +c_ref +[0-9]+ ticks +1\.00x +ok ' "$tmp/f" || err "--bench: no c_ref timing at 1.00x"
[ "$(grep -cE '^count_facing +[a-z0-9_]+ +[0-9]+ ticks +[0-9.]+x +ok ' "$tmp/f")" -eq \
  "$(grep -cE '^count_facing +[a-z0-9_]+ +ok ' "$tmp/a")" ] || err "--bench: not every count_facing line timed"

"$sv" check --seed 5 --function extrude --bench >"$tmp/x" 2>&1 || err "--bench --function extrude failed"
[ "$(grep -cE '^extrude +[a-z0-9_]+ +[0-9]+ ticks +[0-9.]+x +ok ' "$tmp/x")" -eq \
  "$(grep -cE '^extrude +[a-z0-9_]+ +ok ' "$tmp/a")" ] || err "--bench: not every extrude line timed"

# expect STATUS ARGS...: the status and a message naming the trouble.
expect() {
  local want=$1 pattern=$2; shift 2
  "$sv" check "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  [ $rc -eq "$want" ] || err "check $* exited $rc, expected $want"
  grep -q -- "$pattern" "$tmp/err" || err "check $*: no '$pattern' in: $(cat "$tmp/err")"
}
expect 2 "unknown variant 'sideways' (known: c_ref " --variant sideways
expect 2 "unknown function 'nope' (known: calculate_facing " --function nope
expect 2 "--seed needs a whole number" --seed -3
expect 2 "--seed needs a value" --seed
expect 2 "unknown argument '--fast'" --fast
expect 2 "--bench takes no value" --bench=1
exit $fail
