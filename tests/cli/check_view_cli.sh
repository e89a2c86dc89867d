#!/usr/bin/env bash
# `shadowvol view` (issue 30) under Xvfb, driven by --script (events keyed
# to frame numbers, the clock one frame per frame drawn):
#   - the window read back from the X server (snap: XGetImage) is, byte
#     for byte, the PNG `shadowvol scene` writes for the same camera,
#     lights and time: at two frames of the walk, and after the mouse has
#     orbited and zoomed the camera (scene --camera takes the camera the
#     view prints);
#   - each key changes what it says and only that: its word of the state
#     line, nothing else of it (time, camera, lights), and the picture not
#     at all where the switch is proved exact (the stencil mode, the
#     stencil pass, each shortcut) or only while an overlay is on;
#     dragging a picked light moves that light alone; . steps the paused
#     clock one frame;
#   - without a display: exit 5 and a message; bad arguments and scripts:
#     exit 2 naming the file and line.
# Frames of 160x128 on a 320x240 screen (CI: at most 320x240).
# usage: check_view_cli.sh PATH/TO/shadowvol
set -u
sv="$1"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d)
xpid=""
cleanup() { [ -n "$xpid" ] && kill "$xpid" 2>/dev/null; rm -rf "$tmp"; }
trap cleanup EXIT
# No wisdom file: the built-in stencil default (auto), whatever `shadowvol
# tune` saved for this user.
export SV_WISDOM="$tmp/no-wisdom"
size=160x128

# expect STATUS ARGS...: exits STATUS with a message on stderr.
expect() {
  local want=$1; shift
  "$sv" view "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  [ $rc -eq "$want" ] || err "view $* exited $rc, expected $want: $(cat "$tmp/err")"
  [ $rc -eq 0 ] || [ -s "$tmp/err" ] || err "view $* printed no message"
}
"$sv" view --help >"$tmp/out" || err "view --help exited $?"
for word in --script --no-hud --stencil --caster-rule "Exit status" "5 no window"; do
  grep -q -- "$word" "$tmp/out" || err "view --help does not mention $word"
done
expect 2 --frames 3
grep -q "shadowvol scene's" "$tmp/err" || err "view --frames: the refusal does not say whose option it is"
expect 2 --sideways
expect 2 --stencil sideways
expect 2 --script "$tmp/missing.script"
printf '0 key M\n1 jump\n' >"$tmp/bad.script"
expect 2 --script "$tmp/bad.script"
grep -q "bad.script:2: unknown event 'jump'" "$tmp/err" || err "a bad script line is not named: $(cat "$tmp/err")"
printf '0 drag middle 1 2 3 4\n' >"$tmp/bad.script"
expect 2 --script "$tmp/bad.script"
# Without a display: its own status, 5, and a message.
env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER "$sv" view --size "$size" >"$tmp/out" 2>"$tmp/err"
rc=$?
[ $rc -eq 5 ] || err "view without a display exited $rc, not 5: $(cat "$tmp/err")"
grep -q "no display" "$tmp/err" || err "view without a display does not say so: $(cat "$tmp/err")"

if ! command -v Xvfb >/dev/null; then
  echo "SKIP: Xvfb (Debian xvfb) not found: the window cannot be opened"
  [ $fail -eq 0 ] && exit 77
  exit 1
fi
# Our own X server on a free display (Xvfb picks it: -displayfd).
Xvfb -displayfd 3 -screen 0 320x240x24 -nolisten tcp 3>"$tmp/display" 2>"$tmp/xvfb.log" &
xpid=$!
for _ in $(seq 1 100); do [ -s "$tmp/display" ] && break; sleep 0.1; done
[ -s "$tmp/display" ] || { echo "FAIL: Xvfb did not start: $(cat "$tmp/xvfb.log")"; exit 1; }
export DISPLAY=":$(head -1 "$tmp/display")" SDL_VIDEODRIVER=x11

# A key SDL does not know: exit 2, naming it and its line.
printf '0 print\n1 key NoSuchKey\n' >"$tmp/bad.script"
expect 2 --size "$size" --script "$tmp/bad.script"
grep -q "line 2: SDL knows no key 'NoSuchKey'" "$tmp/err" || err "an unknown key is not named: $(cat "$tmp/err")"

# 1. Frames 0 and 3 of the walk against scene's frames 0 and 3.
cat >"$tmp/walk.script" <<SCRIPT
0 snap $tmp/view0.png
3 snap $tmp/view3.png
3 print
SCRIPT
"$sv" view --size "$size" --fps 8 --no-hud --script "$tmp/walk.script" >"$tmp/walk.out" 2>"$tmp/err" \
  || err "view --script walk exited $?: $(cat "$tmp/err")"
"$sv" scene --size "$size" --fps 8 --frames 4 --no-check --no-truth --out "$tmp/scene" >/dev/null 2>"$tmp/err" \
  || err "scene exited $?: $(cat "$tmp/err")"
cmp -s "$tmp/view0.png" "$tmp/scene/frame_000.png" || err "the window at frame 0 is not scene's frame 0"
cmp -s "$tmp/view3.png" "$tmp/scene/frame_003.png" || err "the window at frame 3 is not scene's frame 3"
cmp -s "$tmp/view0.png" "$tmp/view3.png" && err "frames 0 and 3 are the same picture: the walk did not move"
grep -q "^frame 3 time 0.375 " "$tmp/walk.out" || err "frame 3 is not at 3/8 s: $(cat "$tmp/walk.out")"

# 2. The mouse orbits and zooms; scene draws the camera the view prints.
cat >"$tmp/orbit.script" <<SCRIPT
1 drag left 80 64 120 50
1 wheel 2
2 snap $tmp/orbit.png
2 print
SCRIPT
"$sv" view --size "$size" --fps 8 --no-hud --script "$tmp/orbit.script" >"$tmp/orbit.out" 2>"$tmp/err" \
  || err "view --script orbit exited $?: $(cat "$tmp/err")"
cam=$(sed -n 's/.* | camera \([^ ]*\) | .*/\1/p' "$tmp/orbit.out")
time=$(sed -n 's/^frame 2 time \([^ ]*\) .*/\1/p' "$tmp/orbit.out")
[ -n "$cam" ] && [ -n "$time" ] || err "view printed no camera or time: $(cat "$tmp/orbit.out")"
"$sv" scene --size "$size" --fps 8 --time "$time:$time" --camera "$cam" --no-check --no-truth \
    --out "$tmp/orbit_scene" >/dev/null 2>"$tmp/err" || err "scene --camera $cam exited $?: $(cat "$tmp/err")"
cmp -s "$tmp/orbit.png" "$tmp/orbit_scene/frame_000.png" || err "the orbited window is not scene's frame for its camera"
cmp -s "$tmp/orbit.png" "$tmp/scene/frame_002.png" && err "the drag and the wheel did not move the camera"

# 3. Each key, one a frame with the clock paused: the state line's words
#    before and after, and the pictures.
#    KEY  WORD-THAT-CHANGES  NEW-VALUE  PICTURE (same as the frame before: an
#    exact switch; differs; restores: the same as two frames before, an
#    overlay off again; any)
steps=(
  "M mode zpass same" "M mode zfail same" "M mode auto same"
  "T stencil bf same" "T stencil db same" "T stencil hier same" "B overlays tiles differs"
  "B overlays - restores" "T stencil auto same"
  "1 shortcuts -23456 same" "1 shortcuts 123456 same" "2 shortcuts 1-3456 same" "2 shortcuts 123456 same"
  "3 shortcuts 12-456 same" "3 shortcuts 123456 same" "4 shortcuts 123-56 same" "4 shortcuts 123456 same"
  "5 shortcuts 1234-6 same" "5 shortcuts 123456 same" "6 shortcuts 12345- same" "6 shortcuts 123456 same"
  "O overlays stencil differs" "O overlays - restores" "V overlays wireframe differs"
  "V overlays - restores" "H hud on differs" "H hud off restores"
  "C caster closed any" "C caster general any" "C caster auto same"
  "L light 0 same" "L light 1 same"
)
{
  echo "0 key Space"
  echo "0 print"
  echo "0 snap $tmp/k0.png"
  n=1
  for s in "${steps[@]}"; do
    set -- $s
    echo "$n key $1"; echo "$n print"; echo "$n snap $tmp/k$n.png"
    n=$((n + 1))
  done
  # Drag light 1 (picked above): only that light's line changes.
  echo "$n drag right 80 64 100 64"; echo "$n print"; echo "$n snap $tmp/k$n.png"; drag=$n; n=$((n + 1))
  # One frame on, paused: only the time changes (by 1/8 s).
  echo "$n key ."; echo "$n print"; step=$n
} >"$tmp/keys.script"
"$sv" view --size "$size" --fps 8 --no-hud --stencil-tile 8 --script "$tmp/keys.script" >"$tmp/keys.out" 2>"$tmp/err" \
  || err "view --script keys exited $?: $(cat "$tmp/err")"
line() { sed -n "/^frame $1 /p" "$tmp/keys.out"; }
switches() { line "$1" | cut -d'|' -f2; }
rest() { line "$1" | cut -d'|' -f4-; } # the camera and the lights
n=1
for s in "${steps[@]}"; do
  set -- $s
  key=$1 word=$2 value=$3 picture=$4
  before=$(switches $((n - 1))) after=$(switches $n)
  # The words of the switches that differ: exactly WORD, now VALUE.
  changed=$(diff <(echo $before | xargs -n2) <(echo $after | xargs -n2) | sed -n 's/^> //p')
  [ "$changed" = "$word $value" ] || err "key $key at frame $n changed '$changed', not '$word $value' (before:$before; after:$after)"
  [ "$(rest $((n - 1)))" = "$(rest $n)" ] || err "key $key at frame $n moved the camera or a light"
  line $n | grep -q "time 0 " || err "key $key at frame $n: the paused clock moved: $(line $n)"
  case $picture in
    same) cmp -s "$tmp/k$((n - 1)).png" "$tmp/k$n.png" || err "key $key ($word $value) changed the picture" ;;
    differs) cmp -s "$tmp/k$((n - 1)).png" "$tmp/k$n.png" && err "key $key ($word $value) did not change the picture" ;;
    restores) cmp -s "$tmp/k$((n - 2)).png" "$tmp/k$n.png" || err "key $key ($word $value) did not bring the picture back" ;;
  esac
  n=$((n + 1))
done
# What the switches say in the frame's own counts.
line 1 | grep -q " zfail 0 " || err "mode zpass drew volumes in z-fail: $(line 1)"
line 2 | grep -q " zfail 0 " && err "mode zfail drew no volume in z-fail: $(line 2)"
line 6 | grep -q "stencil_method hier" || err "T did not make the pass hier: $(line 6)"
line 10 | grep -q " reach 0 " || err "shortcut 1 off still skipped volumes out of reach: $(line 10)"
# The dragged light: its line alone changed, and the picture.
[ "$(switches $((drag - 1)))" = "$(switches $drag)" ] || err "the light drag changed a switch"
# (Field 1, the frame's number, differs from line to line.)
a=$(line $((drag - 1)) | tr '|' '\n' | grep -n . | tail -n +2) b=$(line $drag | tr '|' '\n' | grep -n . | tail -n +2)
moved=$(diff <(echo "$a") <(echo "$b") | sed -n 's/^> \([0-9]*\):.*/\1/p' | tr '\n' ' ')
light1=$(line $drag | tr '|' '\n' | grep -n "^ light 1 " | cut -d: -f1)
[ "$(echo "$moved" | sed 's/^3 //')" = "$light1 " ] \
  || err "the light drag changed fields '$moved', not light 1's ($light1) and the counts (3) alone"
cmp -s "$tmp/k$((drag - 1)).png" "$tmp/k$drag.png" && err "dragging light 1 did not change the picture"
line $step | grep -q "time 0.125 " || err "the . key did not step the paused clock one frame: $(line $step)"
exit $fail
