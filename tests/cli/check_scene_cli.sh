#!/usr/bin/env bash
# `shadowvol scene` (issue 13): the demo scene, and every animated real
# character of ../shared/models on the ground under a point, a spot and a
# directional light, must play with every frame identical to the full
# frame (no shortcuts) and agreeing with the ray-cast truth, at two thread
# counts with the same bytes; each kind of bad input must end with its
# documented exit status and a message, never a crash.
# usage: check_scene_cli.sh PATH/TO/shadowvol DEMO_SCENE SHARED_MODELS_DIR [SIZE] [bundled|shared]
# (bundled: the demo scene, the bench rows and bad input; shared: the animated
# real characters alone, exit 77 when their folder is missing)
set -u
sv="$1"; demo="$2"; shared="$3"; size="${4:-320x256}"; set="${5:-bundled}"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# No wisdom file: the built-in stencil default (auto), whatever `shadowvol
# tune` saved for this user.
export SV_WISDOM="$tmp/no-wisdom"
cd "$tmp"

# Every animated real character, on the ground, under the three light kinds:
# the entry cli_scene_shared_models alone (exit 77 without the folder).
if [ "$set" = shared ]; then
  [ -d "$shared" ] || { echo "SKIP: $shared not found: the animated characters cannot be played"; exit 77; }
  for m in Fox CesiumMan RobotExpressive RiggedFigure; do
    f="$shared/$m.glb"
    [ -f "$f" ] || { err "missing $f"; continue; }
    "$sv" scene "$f" --ground --frames 3 --fps 4 --size "$size" --out "$tmp/$m" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    tail -4 "$tmp/out"
    [ $rc -eq 0 ] || err "scene $m exited $rc: $(tail -5 "$tmp/out") $(cat "$tmp/err")"
  done
  # The open character (issue 27, ../shared/models/open): two frames of each
  # of its 16 animations under one point light, z-pass and z-fail by turns,
  # under --caster-rule auto; the paper's rule (closed) must fail it.
  f="$shared/open/Zombie_Basic.glb"
  if [ -f "$f" ]; then
    for a in $(seq 0 15); do
      mode=zpass; [ $((a % 2)) -eq 1 ] && mode=zfail
      "$sv" scene "$f" --ground --animation $a --frames 2 --fps 2 --light point:auto --mode $mode \
          --size "$size" --out "$tmp/zombie$a" >"$tmp/out" 2>"$tmp/err"
      rc=$?
      [ $rc -eq 0 ] || err "scene Zombie_Basic --animation $a --mode $mode exited $rc: $(tail -5 "$tmp/out") $(cat "$tmp/err")"
    done
    echo "Zombie_Basic: 16 animations, 2 frames each, passed under --caster-rule auto"
    # (At 320x256 whatever the test size: the sanitizer build's smaller
    # frames show the paper's rule no pixel wrong off the boundary.)
    "$sv" scene "$f" --ground --animation 3 --frames 2 --fps 2 --light point:auto --caster-rule closed \
        --size 320x256 --no-check --out "$tmp/zombie_closed" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    [ $rc -eq 1 ] || err "scene Zombie_Basic --caster-rule closed exited $rc, not 1 (the paper's rule should fail an open character)"
  else
    err "missing $f"
  fi
  exit $fail
fi

# The demo scene: its own lights, camera and walk cycle.
"$sv" scene --size "$size" --frames 4 --json "$tmp/demo.json" --out "$tmp/demo" >"$tmp/out" 2>"$tmp/err"
rc=$?
cat "$tmp/out"
[ $rc -eq 0 ] || err "scene (the demo) exited $rc: $(cat "$tmp/err")"
grep -q '^PASSED' "$tmp/out" || err "the demo scene did not print PASSED"
grep -q '"schema": "shadowvol-scene/1"' "$tmp/demo.json" || err "JSON without its schema"
grep -q '"passed": true' "$tmp/demo.json" || err "JSON does not say passed"
grep -q '"stencil": "auto"' "$tmp/demo.json" || err "JSON does not name the stencil method (auto by default)"
grep -q '"caster_rule": "auto"' "$tmp/demo.json" || err "JSON does not name the caster rule (auto by default)"
grep -q '"ground_hints": true' "$tmp/demo.json" || err "JSON does not say the ground hints are used (the default)"
# The terrain is declared ground in the file: inspect says it keeps the paper's rule, and why.
"$sv" inspect "$demo" >"$tmp/inspect" 2>"$tmp/err" || err "inspect (the demo scene): $(cat "$tmp/err")"
grep -A1 '^terrain' "$tmp/inspect" | grep -q "paper's rule: declared ground" \
  || err "inspect does not say the demo terrain keeps the paper's rule as declared ground: $(grep -A1 '^terrain' "$tmp/inspect")"
for f in frame_000 frame_003 contact; do
  [ "$(head -c 8 "$tmp/demo/$f.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] \
    || err "demo/$f.png is not a PNG"
done
# The same frames on one thread and on three: the same bytes.
for t in 1 3; do
  "$sv" scene --size 160x128 --frames 3 --threads $t --no-truth --out "$tmp/t$t" >"$tmp/out" 2>"$tmp/err" \
    || err "scene --threads $t exited $?: $(cat "$tmp/err")"
done
for k in 000 001 002; do
  cmp -s "$tmp/t1/frame_$k.png" "$tmp/t3/frame_$k.png" || err "frame $k differs between 1 and 3 threads"
done
# --full renders the frames with no shortcut: the same pictures.
"$sv" scene --size 160x128 --frames 3 --full --no-truth --out "$tmp/full" >"$tmp/out" 2>"$tmp/err" \
  || err "scene --full exited $?: $(cat "$tmp/err")"
for k in 000 001 002; do
  cmp -s "$tmp/t1/frame_$k.png" "$tmp/full/frame_$k.png" || err "frame $k differs with --full"
done

# The benchmark's per-frame rows: every figure with its check.
"$sv" bench --scene --quick --json "$tmp/bench.json" >"$tmp/out" 2>"$tmp/err"
rc=$?
cat "$tmp/out"
[ $rc -eq 0 ] || err "bench --scene exited $rc: $(cat "$tmp/err")"
grep -q 'check: 4 of 4 frames equal their full frame, 4 of 4 the same bytes' "$tmp/out" \
  || err "bench --scene did not print its check"
grep -q '^terrain under a headlight .* straddles | cull ' "$tmp/out" || err "the terrain was not culled"
grep -q '^character inside the lamp .* inside | no cull ' "$tmp/out" || err "the character was culled"
grep -q '"schema": "shadowvol-scene-bench/1"' "$tmp/bench.json" || err "bench JSON without its schema"
# The caster rule (issue 27): closed against auto, the same pictures.
grep -qE '^closed +[0-9.]+ +[0-9]+ +[0-9]+ +yes$' "$tmp/out" || err "bench --scene: no caster-rule row for closed"
grep -qE '^auto +[0-9.]+ +[0-9]+ +[0-9]+ +yes$' "$tmp/out" \
  || err "bench --scene: auto's frames differ from closed's, or no row"
grep -q '"caster_rules"' "$tmp/bench.json" || err "bench JSON without its caster_rules"
"$sv" bench --scene --caster-rule sideways >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] || err "bench --scene --caster-rule sideways did not exit 2"
"$sv" bench --caster-rule closed >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] || err "bench --caster-rule without --scene did not exit 2"

# expect STATUS ARGS...: exits STATUS with a message on stderr.
expect() {
  local want=$1; shift
  "$sv" scene --size 64x48 --frames 1 --no-truth --no-check --out "$tmp/bad" "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  [ $rc -eq "$want" ] || err "scene $* exited $rc, expected $want: $(cat "$tmp/err")"
  [ $rc -eq 0 ] || [ -s "$tmp/err" ] || err "scene $* printed no message"
  [ $rc -lt 126 ] || err "scene $* crashed ($rc)"
}
expect 2 --frames 0
expect 2 --frames 3 --time 0:1
expect 2 --time 1:0
expect 2 --time 0
expect 2 --fps 0
expect 2 --fps nan
expect 2 --threads 0
expect 2 --size 10
expect 2 --skinning avx1024
expect 2 --animation ""
expect 2 --light spot:0,3,0,0,-1,0,50,40
expect 2 --sideways
expect 2 --stencil sideways
expect 2 --stencil hier --stencil-tile 12
grep -q -- '--stencil-tile needs 4, 8, 16 or 32' "$tmp/err" || err "--stencil-tile 12: the message does not list the sides: $(cat "$tmp/err")"
expect 2 --stencil-tile
expect 0 --stencil hier --stencil-tile 4
expect 2 --caster-rule sideways
expect 2 --mode sideways
expect 3 "$tmp/missing.glb"
expect 3 --animation no-such-walk
expect 3 --add "$tmp/missing.glb"
printf 'not a gltf' >"$tmp/junk.glb"
expect 3 "$tmp/junk.glb"

# One animation per added file (issue 30): FILE[@...]:ANIMATION, by name or
# index; a refusal names the file it is about; a file name with a ':' is
# written with a ':' after it.
"$sv" scene --size 64x48 --frames 1 --no-truth --no-check --out "$tmp/add" \
    --add "$demo@30,0,0:0" >"$tmp/out" 2>"$tmp/err" || err "scene --add DEMO@30,0,0:0 exited $?: $(cat "$tmp/err")"
[ "$(grep -c "animation 0 'walk'" "$tmp/out")" -eq 2 ] \
  || err "scene --add DEMO:0: the added file does not play its walk: $(head -4 "$tmp/out")"
expect 0 --add "$demo:walk"
expect 3 --add "$demo:run"
grep -q "^shadowvol scene: $demo: no animation 'run'; the animations are: 0 'walk'" "$tmp/err" \
  || err "--add DEMO:run: the refusal does not name the added file with its list: $(cat "$tmp/err")"
# What a new user tried: --animation with only --add files is the scene file's; the note says so.
expect 3 --add "$demo" --animation 3
grep -q -- "note: --animation is the scene file's .*--add FILE:ANIMATION" "$tmp/err" \
  || err "--add DEMO --animation 3: no note on --add FILE:ANIMATION: $(cat "$tmp/err")"
expect 0 "$demo:walk"
expect 2 "$demo:walk" --animation 0
grep -q "given twice" "$tmp/err" || err "FILE:A with --animation: the refusal does not say why: $(cat "$tmp/err")"
cp "$demo" "$tmp/a:b.glb"
expect 0 --add "$tmp/a:b.glb@0,0,0:"
expect 0 --add "$tmp/a:b.glb:walk"
expect 3 --add "$tmp/a:b.glb"
grep -q "$tmp/a" "$tmp/err" || err "--add a:b.glb: the refusal does not name the file it tried: $(cat "$tmp/err")"

# A hostile argument (100 KB, with control characters and bytes that are
# not UTF-8) is quoted bounded and printable in the refusal (issue 17): at
# most 300 input bytes per quote (sv::kGltfMaxQuotedBytes), a few quotes.
huge="point:1,2,$(printf '\001\377%.0s' $(seq 1 50000))"
for opt in --light --camera --add --sideways; do
  want=2; [ "$opt" = --add ] && want=3  # --add takes any file name; it cannot be opened
  if [ "$opt" = --sideways ]; then args=("--sideways$huge"); else args=("$opt" "$huge"); fi
  "$sv" scene --size 64x48 --frames 1 --no-truth --no-check --out "$tmp/bad" "${args[@]}" \
    >"$tmp/out" 2>"$tmp/err"
  rc=$?
  [ $rc -eq $want ] || err "scene $opt with a 100 KB argument exited $rc, expected $want"
  bytes=$(wc -c <"$tmp/err")
  [ "$bytes" -gt 0 ] && [ "$bytes" -le 4800 ] \
    || err "scene $opt with a 100 KB argument printed $bytes bytes (1..4800 expected)"
  LC_ALL=C grep -q $'[\x01\xff]' "$tmp/err" && err "scene $opt echoed raw control or non-UTF-8 bytes"
done
exit $fail
