#!/usr/bin/env bash
# The shadowvol program as a user meets it: `bench --quick` runs every row,
# checks every call against the reference and exits 0; bad arguments get a
# message on stderr and exit status 2 (3 for a model that cannot be loaded);
# --help goes to stdout with status 0.
# usage: check_cli.sh PATH/TO/shadowvol
set -u
sv="$1"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

routines='calculate_facing|calculate_cull_bits|count_facing|count_facing_cull|create_sil_triangles|create_cap_triangles|create_shadow_volume|create_shadow_volume_cull'
out=$("$sv" bench --quick 2>"$tmp/err"); rc=$?
[ $rc -eq 0 ] || err "bench --quick exited $rc: $(cat "$tmp/err")"
rows=$(printf '%s\n' "$out" | grep -cE "^($routines) ")
okrows=$(printf '%s\n' "$out" | grep -E "^($routines) " | grep -cE '\| ok$')
# 6 routines x 3 variants + calculate_facing and calculate_cull_bits (c_ref), x 2 regimes
[ "$rows" -ge 40 ] || err "expected at least 40 table rows, got $rows"
[ "$rows" -eq "$okrows" ] || err "$((rows - okrows)) rows not checked ok"
printf '%s\n' "$out" | grep -q 'FAILED' && err "a row FAILED its correctness check"
for field in '^cpu ' '^isa ' '^tsc ' '^timer' '^overhead' '^build' '^model .*character_1344.glb' \
             'real characters' '^lights .*point lights' 'facing [0-9.]+% \(' 'silhouette [0-9.]+% \(' \
             '^cull .*of the triangles outside'; do
  printf '%s\n' "$out" | grep -qE "$field" || err "no '$field' in the header"
done

expect_status() { # expected-status description args...
  local want=$1; shift; local what=$1; shift
  "$sv" "$@" >"$tmp/out" 2>"$tmp/err"; local got=$?
  [ $got -eq "$want" ] || err "$what: exit $got, want $want ($(head -c 300 "$tmp/err"))"
  if [ "$want" -ne 0 ]; then
    [ -s "$tmp/err" ] || err "$what: no message on stderr"
  else
    [ -s "$tmp/out" ] || err "$what: nothing on stdout"
  fi
}
expect_status 0 "help" help
expect_status 0 "--help" --help
expect_status 0 "bench --help" bench --help
expect_status 2 "no command"
expect_status 2 "unknown command" frobnicate
expect_status 2 "unknown option" bench --frobnicate
expect_status 2 "--runs 0" bench --runs 0
expect_status 2 "--runs abc" bench --runs abc
expect_status 2 "--rounds 0" bench --rounds 0
expect_status 2 "--rounds 65" bench --rounds 65
expect_status 2 "--regime foo" bench --regime foo
expect_status 2 "unknown routine" bench --routine no_such_routine
expect_status 2 "unknown variant" bench --variant no_such_variant
expect_status 2 "--timer foo" bench --timer foo
expect_status 2 "--light with three numbers" bench --light 1,2,3
grep -q -- '--light needs x,y,z,w' "$tmp/err" || err "--light: the message does not say what it needs"
expect_status 2 "--light with five numbers" bench --light 1,2,3,1,5
expect_status 2 "--light not numbers" bench --light a,b,c,d
expect_status 2 "--light w neither 0 nor 1" bench --light 1,2,3,0.5
expect_status 2 "--light nan" bench --light nan,0,0,1
expect_status 2 "--light directional 0,0,0" bench --light 0,0,0,0
expect_status 2 "--isa unknown level" bench --isa avx9000
grep -q -- '--isa must be one of c, sse2' "$tmp/err" || err "--isa: the message does not list the levels"
expect_status 2 "--variant above --isa" bench --isa c --variant sse2_paper
expect_status 2 "--facing-ratio 1.5" bench --facing-ratio 1.5
expect_status 2 "--silhouette-ratio 0" bench --silhouette-ratio 0
expect_status 2 "--json into a missing folder" bench --json "$tmp/no/such/dir/b.json"
expect_status 3 "--model missing file" bench --model "$tmp/no_such_model.glb" --json "$tmp/failed.json"
grep -q 'no_such_model.glb' "$tmp/err" || err "--model: the message does not name the file"
[ -e "$tmp/failed.json" ] && err "--json: a run that failed left a JSON file behind"
printf 'not a glTF file\n' >"$tmp/broken.glb"
expect_status 3 "--model not glTF" bench --model "$tmp/broken.glb"
expect_status 3 "--model folder without glTF" bench --model "$tmp"

# --scaling: its options need it, and the cycle table's fixed-light options do not apply.
expect_status 0 "bench --help mentions --scaling" bench --help
grep -q -- '--scaling' "$tmp/out" || err "bench --help does not describe --scaling"
expect_status 2 "--plot without --scaling" bench --plot "$tmp/p.svg"
expect_status 2 "--max-triangles without --scaling" bench --max-triangles 5000
expect_status 2 "--scaling --max-triangles 0" bench --scaling --max-triangles 0
expect_status 2 "--scaling --regime fixed" bench --scaling --regime fixed
expect_status 3 "--scaling --model (a missing file)" bench --scaling --model "$tmp/x.glb"
expect_status 2 "--scaling --model synthetic" bench --scaling --model synthetic
expect_status 2 "--scaling --light" bench --scaling --light 0,10,0,0
expect_status 2 "--scaling with a value" bench --scaling=yes
expect_status 2 "--scaling --json - --plot -" bench --scaling --json - --plot -
expect_status 2 "--scaling --plot into a missing folder" bench --scaling --plot "$tmp/no/such/dir/p.svg" --json "$tmp/s.json"
[ -e "$tmp/s.json" ] && err "--scaling: a run that failed left a JSON file behind"
# The smallest scaling run: one routine, the meshes up to 2000 triangles.
expect_status 0 "--scaling --quick" bench --scaling --quick --max-triangles 2000 --routine count_facing --plot "$tmp/s.svg"
grep -qE '^character_1344 +1344 ' "$tmp/out" || err "--scaling: no row of the generated character"
grep -qE '^character_12096 ' "$tmp/out" && err "--scaling: --max-triangles 2000 ran a larger mesh"
grep -q '^left out  character_12096' "$tmp/out" || err "--scaling: the header does not say what was left out"
grep -q '<polyline' "$tmp/s.svg" || err "--scaling --plot: no polyline in the SVG"

# --isa c: the C variants only, and the header says why the others are not run.
expect_status 0 "--isa c" bench --quick --isa c --routine count_facing --regime fixed
grep -qE '^count_facing +sse2_paper' "$tmp/out" && err "--isa c: sse2_paper rows ran"
grep -q '^skipped   variant sse2_paper: above the ISA limit c (--isa)' "$tmp/out" || err "--isa c: no skipped line"
grep -qE '^count_facing +c_branchless' "$tmp/out" || err "--isa c: no c_branchless row"
# --light: the fixed regime uses it, and the header prints it.
expect_status 0 "--light directional" bench --quick --light 0,10,0,0 --routine calculate_facing
grep -q -- '--light at (0, 10, 0, 0)' "$tmp/out" || err "--light: the header does not show it"

# --limits: the machine's rates and a floor per routine after the table.
expect_status 2 "--limits --scaling" bench --limits --scaling
expect_status 2 "--limits with a value" bench --limits=yes
expect_status 0 "--limits" bench --quick --limits --regime moving --routine count_facing --routine create_sil_triangles --routine create_shadow_volume
grep -q '^limits: ' "$tmp/out" || err "--limits: no limits section"
for rate in 'scalar byte loads' 'stores, L1'; do
  grep -qE "^  .*$rate.* [0-9]+\.[0-9]+ " "$tmp/out" || err "--limits: no rate '$rate'"
done
grep -qE '^  .*scalar byte loads.* 0\.00 ' "$tmp/out" && err "--limits: a zero load rate"
no_avx2=0
if grep -q 'not measured (no AVX2)' "$tmp/out"; then
  echo "SKIPPED: no AVX2 here: --limits prints no floors (the entry exits 77 when all else passed)"
  no_avx2=1
else
  for r in count_facing create_sil_triangles create_shadow_volume; do
    line=$(grep -E "^$r +[0-9]+ " "$tmp/out" | tail -1)
    [ -n "$line" ] || { err "--limits: no floor row for $r"; continue; }
    # floor, streaming floor, load port, lookups, store: numbers; the floor
    # is the larger port; the streaming floor (no lookups) is not above it
    set -- $line
    [ "$2" -gt 0 ] || err "--limits: $r floor $2 is not positive"
    [ "$2" -ge "$4" ] && [ "$2" -ge "$6" ] || err "--limits: $r floor $2 below a port ($4, $6)"
    [ "$4" -ge "$5" ] || err "--limits: $r lookups $5 above the load port's $4"
    [ "$3" -gt 0 ] && [ "$3" -le "$2" ] || err "--limits: $r streaming floor $3 not in (0, floor $2]"
  done
  grep -qE '^count_facing_cull +[0-9]+ ' "$tmp/out" && err "--limits: a floor for a routine not run"
  # the AVX2 forms of the primitives, under the ISA limit
  expect_status 0 "--limits --isa avx2" bench --quick --limits --isa avx2 --regime moving --routine count_facing
  grep -qE '^  ymm loads, L1 .* [0-9]+\.[0-9] bytes per tick' "$tmp/out" || err "--limits --isa avx2: no ymm rates"
  grep -qE '^  vpgatherdd ymm lanes .* [0-9]+\.[0-9]+ per tick' "$tmp/out" || err "--limits --isa avx2: no ymm gather rate"
  grep -qE '^  vpgatherdd ymm lanes .* 0\.00 per tick' "$tmp/out" && err "--limits --isa avx2: a zero gather rate"
  expect_status 0 "--limits --isa sse2" bench --quick --limits --isa sse2 --regime moving --routine count_facing
  grep -q 'not measured (no AVX2)' "$tmp/out" || err "--limits --isa sse2: does not say the vector rates are not measured"
fi

[ $fail -eq 0 ] && echo "shadowvol CLI: $rows rows checked ok, argument errors and help behave"
[ $fail -eq 0 ] && [ $no_avx2 -eq 1 ] && exit 77
exit $fail
