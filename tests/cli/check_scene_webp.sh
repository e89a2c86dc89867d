#!/usr/bin/env bash
# `shadowvol scene --webp` (issue 30): the demo scene's frames as an
# animated WebP, decoded back by sv_webp_frames (libwebpdemux's
# WebPAnimDecoder): every frame the bytes of the PNG frame scene wrote for
# the same options, each 1/F s long, looping; a file that cannot be
# written is refused naming it. In a build without libwebp (CHECKER none)
# --webp must be refused with exit 2 and a message, and the entry skips.
# usage: check_scene_webp.sh PATH/TO/shadowvol PATH/TO/sv_webp_frames|none
set -u
sv="$1"; checker="$2"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

small=(--size 64x48 --frames 1 --no-check --no-truth --out "$tmp/small")
if [ "$checker" = none ]; then
  "$sv" scene "${small[@]}" --webp "$tmp/a.webp" >"$tmp/out" 2>"$tmp/err"
  rc=$?
  [ $rc -eq 2 ] || err "scene --webp in a build without libwebp exited $rc, not 2"
  grep -q "built without libwebp" "$tmp/err" || err "no message on libwebp: $(cat "$tmp/err")"
  [ $fail -eq 0 ] || exit 1
  echo "SKIP: this build has no libwebp (libwebp-dev): --webp refused as it should be"
  exit 77
fi

# Four frames of the walk at 6 fps, both stencil methods' bytes the same.
for stencil in bf hier; do
  "$sv" scene --size 160x128 --frames 4 --fps 6 --stencil $stencil --no-check --no-truth \
      --out "$tmp/$stencil" --webp "$tmp/$stencil.webp" >"$tmp/out" 2>"$tmp/err"
  rc=$?
  [ $rc -eq 0 ] || err "scene --webp (--stencil $stencil) exited $rc: $(cat "$tmp/err")"
  grep -q "animation: $tmp/$stencil.webp" "$tmp/out" || err "scene does not name the animation it wrote"
  [ "$(head -c 4 "$tmp/$stencil.webp")" = RIFF ] || err "$stencil.webp is not a RIFF file"
  "$checker" "$tmp/$stencil.webp" "$tmp/$stencil" 6 || err "the WebP's frames (--stencil $stencil) are not the PNGs' bytes"
done
cmp -s "$tmp/bf.webp" "$tmp/hier.webp" || err "bf and hier wrote different animations"
# The checker itself sees a frame that is not the PNG's.
cp "$tmp/bf/frame_001.png" "$tmp/bf/frame_002.png"
"$checker" "$tmp/bf.webp" "$tmp/bf" 6 >"$tmp/out" && err "the checker missed a frame that differs"
grep -q "frame 2: .*DIFFERS" "$tmp/out" || err "the checker did not name frame 2: $(cat "$tmp/out")"

# A file that cannot be written: exit 2, naming it; an empty name: exit 2.
"$sv" scene "${small[@]}" --webp /proc/version/a.webp >"$tmp/out" 2>"$tmp/err"
rc=$?
[ $rc -eq 2 ] || err "scene --webp /proc/version/a.webp exited $rc, not 2"
grep -q "/proc/version/a.webp" "$tmp/err" || err "the refusal does not name the file: $(cat "$tmp/err")"
"$sv" scene "${small[@]}" --webp "" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] || err "scene --webp '' did not exit 2"
exit $fail
