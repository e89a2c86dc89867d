#!/usr/bin/env bash
# `shadowvol bench --scene --preset NAME --size WxH` (issue 28): the table
# of passes for each preset (simple, knights, demo, a file) has a stencil
# row per method (bf, db, hier) at 1 thread and every core, each checked
# in the same run (every light's stencil equal to bf's), the same rows in
# the JSON with their frame and run counts, and the bandwidth rows; `bench
# --figure1` writes seed 004's Figure 1; bad input ends with its
# documented exit status and a message.
# usage: check_scene_bench.sh PATH/TO/shadowvol DEMO_SCENE
set -u
sv="$1"; demo="$2"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

for preset in simple knights demo "$demo"; do
  "$sv" bench --scene --preset "$preset" --size 160x128 --quick --json "$tmp/p.json" \
    >"$tmp/out" 2>"$tmp/err"
  rc=$?
  [ $rc -eq 0 ] || { err "--preset $preset exited $rc: $(cat "$tmp/err")"; continue; }
  for m in bf db hier auto; do
    grep -qE "^stencil +$m +[-0-9]+ +1 +[0-9.]+ +[0-9.]+ +[0-9]+ +[0-9.]+ +[0-9]+ +yes$" "$tmp/out" \
      || err "--preset $preset: no checked 1-thread row for $m: $(cat "$tmp/out")"
  done
  rows=$(grep -c '"pass": "stencil"' "$tmp/p.json")
  [ "$rows" -ge 3 ] || err "--preset $preset: $rows stencil rows in the JSON"
  grep -q '"frames": 2, "runs": 2, "frames_equal_to_bf": 2}' "$tmp/p.json" \
    || err "--preset $preset: the JSON lacks the rows' counts and check"
  if grep -q '"frames_equal_to_bf": [01]}' "$tmp/p.json"; then
    err "--preset $preset: a method's stencil differs from bf's"
  fi
done
# hier tests fewer pixels than bf on the crowd (the ratio is printed).
"$sv" bench --scene --preset knights --size 320x256 --quick >"$tmp/out" 2>&1 \
  || err "knights at 320x256: $(cat "$tmp/out")"
bf=$(awk '$1 == "stencil" && $2 == "bf" && $4 == 1 {print $7; exit}' "$tmp/out")
hier=$(awk '$1 == "stencil" && $2 == "hier" && $4 == 1 {print $7; exit}' "$tmp/out")
[ -n "$bf" ] && [ -n "$hier" ] && [ "$hier" -lt "$bf" ] \
  || err "knights: hier tested ${hier:-?} pixels, bf ${bf:-?}"
# The tile-size rows: hier on 1 thread at each of 4, 8, 16 and 32, checked.
for t in 4 8 16 32; do
  grep -qE "^stencil +hier +$t +1 .* yes$" "$tmp/out" || err "knights: no checked row for hier's tile $t"
done

# The bandwidth rows (seed 004's Table 1 accounting): printed and in the JSON.
grep -q "^bandwidth per frame, MB" "$tmp/out" || err "knights: no bandwidth table"
"$sv" bench --scene --preset simple --size 160x128 --quick --json "$tmp/b.json" >/dev/null 2>&1
[ "$(grep -c '"bw_total": ' "$tmp/b.json")" -ge 3 ] || err "simple: no bw_total in the JSON rows"

# auto's rule measured (bench --stencil-rule): a row per light, each checked,
# the fit printed and in the JSON. --quick: of the models the bundled
# character alone (every model took 145 s of the sanitizer build).
"$sv" bench --stencil-rule --preset simple --size 160x128 --quick --json "$tmp/r.json" \
  >"$tmp/out" 2>"$tmp/err" || err "--stencil-rule exited $?: $(cat "$tmp/err")"
grep -qE "^simple +0 +0 +[0-9]+ .* (bf|hier) +yes$" "$tmp/out" \
  || err "--stencil-rule: no checked row for simple's light: $(cat "$tmp/out")"
grep -qE "^character_1344 zfail" "$tmp/out" \
  || err "--stencil-rule: no render-table model's z-fail row"
grep -qE "^koala " "$tmp/out" && err "--stencil-rule --quick: drew more models than the bundled character"
grep -q "lights. Total stencil ms: bf " "$tmp/out" || err "--stencil-rule: no fit line"
grep -q '"hier_from_area_per_piece": ' "$tmp/r.json" || err "--stencil-rule: no threshold in the JSON"
grep -q '"equal": false' "$tmp/r.json" && err "--stencil-rule: hier's stencil differs from bf's"

# Seed 004's Figure 1: four PNGs, the composed shadow equal to the correct
# one and hier's stencil to bf's (the tool's own checks), usage errors.
mkdir -p "$tmp/fig"
"$sv" bench --figure1 --preset simple --size 160x100 --out "$tmp/fig" >"$tmp/out" 2>&1 \
  || err "--figure1 exited $?: $(cat "$tmp/out")"
for k in correct lowres boundary composed; do
  [ -s "$tmp/fig/simple_$k.png" ] || err "--figure1: no simple_$k.png"
done
grep -q "composed = correct: yes (0 pixels differ); hier's stencil = bf's: yes" "$tmp/out" \
  || err "--figure1: $(cat "$tmp/out")"
"$sv" bench --figure1 --preset simple >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] || err "--figure1 without --out did not exit 2"
"$sv" bench --frame --stencil nope >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] || err "bench --frame --stencil nope did not exit 2"
grep -q "stencil" "$tmp/err" || err "bench --frame --stencil nope: no message"

# Bad input.
"$sv" bench --scene --preset "$tmp/none.glb" --quick >"$tmp/out" 2>"$tmp/err"
[ $? -eq 3 ] || err "a missing --preset file did not exit 3"
grep -q "none.glb" "$tmp/err" || err "a missing --preset file: no message naming it"
for bad in "--size 0x5" "--size 9000x10" "--size 12" "--preset="; do
  # shellcheck disable=SC2086
  "$sv" bench --scene $bad >"$tmp/out" 2>"$tmp/err"
  [ $? -eq 2 ] || err "bench --scene $bad did not exit 2"
  [ -s "$tmp/err" ] || err "bench --scene $bad: no message"
done
"$sv" bench --preset simple >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] || err "--preset without --scene did not exit 2"
"$sv" bench --size 64x64 >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] || err "--size without --scene did not exit 2"

[ $fail -eq 0 ] && echo "bench --scene presets: OK"
exit $fail
