#!/usr/bin/env bash
# The full sweep of issue 27: every animation of the open character
# (../shared/models/open/Zombie_Basic.glb, or MODEL), every frame 1/FPS s
# apart over the animation's whole range, under a point, a spot and a
# directional auto light, in z-pass and in z-fail, each frame checked
# against its full frame and the ray truth (shadowvol scene). Prints one
# row per animation and mode: frames, frames equal to their full frame,
# stencil pixels off a shadow boundary that disagree with the truth (all
# lights and frames), the exit status.
# usage: tools/open_sweep.sh [BUILD_DIR] [--size WxH] [--fps F] [--caster-rule R] [MODEL]
set -u
repo=$(cd "$(dirname "$0")/.." && pwd)
build="$repo/build" size=320x256 fps=8 rule=auto model="$repo/../shared/models/open/Zombie_Basic.glb"
while [ $# -gt 0 ]; do
  case "$1" in
    --size) size="$2"; shift 2 ;;
    --fps) fps="$2"; shift 2 ;;
    --caster-rule) rule="$2"; shift 2 ;;
    -h|--help) sed -n 2,9p "$0"; exit 0 ;;
    *.glb) model="$1"; shift ;;
    *) build="$1"; shift ;;
  esac
done
sv="$build/shadowvol"
[ -x "$sv" ] || { echo "open_sweep: no $sv (build first)" >&2; exit 2; }
[ -f "$model" ] || { echo "open_sweep: no $model" >&2; exit 2; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
count=$("$sv" scene "$model" --animation 999999 --frames 1 --size 8x8 --out "$work/x" 2>&1 \
  | grep -o ", [0-9]* '[^']*'" | wc -l)
count=$((count + 1)) # the list reads "0 'A', 1 'B', ...": the first has no comma
[ "$count" -gt 0 ] || { echo "open_sweep: $model has no animation" >&2; exit 2; }
printf '%-4s %-14s %-6s %7s %7s %9s %5s\n' anim name mode frames "=full" "off-bound" exit
failed=0
for a in $(seq 0 $((count - 1))); do
  for mode in zpass zfail; do
    out="$work/a$a$mode"
    # The animation's range, from the header a one-frame run prints.
    range=$("$sv" scene "$model" --animation $a --frames 1 --size 8x8 --no-check --no-truth \
      --out "$work/r" 2>/dev/null | grep -o "([0-9.]* s to [0-9.]* s)" | head -1 | tr -d '()s' )
    from=$(echo "$range" | awk '{print $1}'); to=$(echo "$range" | awk '{print $3}')
    "$sv" scene "$model" --ground --animation $a --time "$from:$to" --fps "$fps" --size "$size" \
      --light point:auto --light spot:auto --light dir:auto --mode $mode --caster-rule "$rule" \
      --json "$out.json" --out "$out" >"$out.txt" 2>&1
    rc=$?
    [ $rc -eq 0 ] || failed=1
    python3 - "$out.json" $a $mode $rc <<'PY'
import json, sys
path, a, mode, rc = sys.argv[1:]
try:
    d = json.load(open(path))
except Exception:
    print("%-4s %-14s %-6s %7s %7s %9s %5s" % (a, "?", mode, "-", "-", "-", rc)); sys.exit()
fr = d["frames"]
same = sum(1 for f in fr if f.get("identical_to_full"))
off = sum(f.get("truth_off_boundary", 0) for f in fr)
print("%-4s %-14s %-6s %7d %7d %9d %5s" % (a, d["animation"][:14], mode, len(fr), same, off, rc))
PY
  done
done
exit $failed
