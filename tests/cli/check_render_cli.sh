#!/usr/bin/env bash
# `shadowvol render`: with no arguments (the bundled character on the
# ground, 1280x1024, both judges) it must pass and write its four PNGs and
# a shadowvol-render/1 document; then each kind of bad input must end with
# its documented exit status and a message, never a crash.
# usage: check_render_cli.sh PATH/TO/shadowvol MODELS_DIR
set -u
sv="$1"; models="$2"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# No wisdom file: the defaults below are the built-in ones, whatever
# `shadowvol tune` saved for this user.
export SV_WISDOM="$tmp/no-wisdom"

cd "$tmp"
"$sv" render --json "$tmp/render.json" >"$tmp/out" 2>"$tmp/err"
rc=$?
cat "$tmp/out"
[ $rc -eq 0 ] || err "render with no arguments exited $rc: $(cat "$tmp/err")"
grep -q '^PASSED' "$tmp/out" || err "render did not print PASSED"
for f in shaded stencil truth; do
  [ "$(head -c 8 "shadowvol-render/$f.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] \
    || err "shadowvol-render/$f.png is not a PNG"
done
# OSMesa is a build package (tools/packages.txt): no context is a failure.
if grep -q 'no Mesa GL context' "$tmp/err"; then
  err "no Mesa GL context: gl_diff.png not written ($(grep 'no Mesa GL context' "$tmp/err"))"
else
  [ -s shadowvol-render/gl_diff.png ] || err "no gl_diff.png although Mesa ran"
fi
grep -q '"schema": "shadowvol-render/1"' "$tmp/render.json" || err "JSON without its schema"
grep -q '"passed": true' "$tmp/render.json" || err "JSON does not say passed"
grep -q '"width": 1280' "$tmp/render.json" || err "the default size is not 1280x1024"
grep -q '"stencil": "auto"' "$tmp/render.json" || err "JSON does not name the stencil method (auto by default)"
grep -q '"stencil_source": "default"' "$tmp/render.json" || err "JSON: the default stencil method's source is not default"

# The stencil method from the wisdom file (shadowvol tune's line for this
# CPU) where --stencil does not say; --stencil and --stencil-tile override
# it; a line for another CPU is not this one's.
cpu=$("$sv" tune --class 0 --no-stencil --dry-run 2>/dev/null | sed -n 's/^cpu  *//p')
[ -n "$cpu" ] || err "tune printed no cpu line"
printf 'shadowvol-wisdom 1\ncpu Other 1/2/3 sse2 X\nstencil bf 8 1.0\ncpu %s\nstencil hier 16 40.0\n' "$cpu" \
  >"$tmp/wisdom"
wisdom_render() { # JSON_FILE ARGS...
  local json=$1; shift
  SV_WISDOM="$tmp/wisdom" "$sv" render --size 96x64 --no-gl --no-truth --out "$tmp/w" --json "$json" "$@" \
    >/dev/null 2>"$tmp/err" || err "render $* with a wisdom file exited $?: $(cat "$tmp/err")"
}
wisdom_render "$tmp/w1.json"
grep -q '"stencil": "hier"' "$tmp/w1.json" && grep -q '"stencil_source": "wisdom"' "$tmp/w1.json" \
  && grep -q '"stencil_tile": 16' "$tmp/w1.json" || err "the wisdom's stencil line did not set the default"
wisdom_render "$tmp/w2.json" --stencil bf --stencil-tile 8
grep -q '"stencil": "bf"' "$tmp/w2.json" && grep -q '"stencil_source": "option"' "$tmp/w2.json" \
  && grep -q '"stencil_tile": 8' "$tmp/w2.json" || err "--stencil did not override the wisdom"
wisdom_render "$tmp/w3.json" --stencil auto
grep -q '"stencil": "auto"' "$tmp/w3.json" && grep -q '"stencil_hier_from_area_per_piece": 40' "$tmp/w3.json" \
  || err "--stencil auto did not take the wisdom's threshold"
# index_lists: one row per volume (the lights' "volumes" summed), each with
# its count and a 16-hex-digit FNV-1a 64 of the list (tools/pin_bytes.sh).
volumes=$(( $(sed -n 's/^ *"volumes": \([0-9]*\),$/\1/p' "$tmp/render.json" | paste -sd+) + 0 ))
rows=$(grep -c '{"light": [0-9]*, "surface": [0-9]*, "zfail": [a-z]*, "indices": [1-9][0-9]*, "silhouette_indices": [0-9]*, "indices_fnv1a64": "[0-9a-f]\{16\}"}' "$tmp/render.json")
[ "$volumes" -gt 0 ] && [ "$rows" = "$volumes" ] || err "index_lists: $rows row(s) for $volumes volume(s)"

# A small scene of every light kind, both modes, written elsewhere.
for mode in zpass zfail; do
  "$sv" render --add "$models/character_1344.glb@0.5,0,0,90,1.5" --ground --light point:auto \
      --light spot:-1,3,1,0.3,-1,-0.2,15,35 --light dir:0.3,-1,0.2 --size 200x160 --mode $mode \
      --out "$tmp/small" >"$tmp/out" 2>"$tmp/err" || err "small scene ($mode) exited $?: $(cat "$tmp/out" "$tmp/err")"
done
[ -s "$tmp/small/stencil.png" ] || err "--out was not used"

# Every stencil method leaves brute force's stencil: the same PNGs, an odd
# size (edge tiles), 3 threads; the JSON names the method.
for m in bf db hier; do
  "$sv" render --add "$models/character_1344.glb@0.5,0,0,90,1.5" --ground --light point:auto \
      --light dir:0.3,-1,0.2 --size 157x93 --threads 3 --no-gl --stencil $m --out "$tmp/m_$m" \
      --json "$tmp/m_$m.json" >"$tmp/out" 2>"$tmp/err" || err "--stencil $m exited $?: $(cat "$tmp/err")"
  grep -q "\"stencil\": \"$m\"" "$tmp/m_$m.json" || err "--stencil $m: the JSON does not name it"
done
for t in 4 32; do
  "$sv" render --add "$models/character_1344.glb@0.5,0,0,90,1.5" --ground --light point:auto \
      --light dir:0.3,-1,0.2 --size 157x93 --threads 3 --no-gl --stencil hier --stencil-tile $t \
      --out "$tmp/m_hier$t" >"$tmp/out" 2>"$tmp/err" || err "--stencil-tile $t exited $?: $(cat "$tmp/err")"
done
for m in db hier hier4 hier32; do
  cmp -s "$tmp/m_bf/stencil.png" "$tmp/m_$m/stencil.png" || err "--stencil $m: stencil.png differs from bf's"
  cmp -s "$tmp/m_bf/shaded.png" "$tmp/m_$m/shaded.png" || err "--stencil $m: shaded.png differs from bf's"
done

# expect STATUS ARGS...: exits STATUS with a message on stderr.
expect() {
  local want=$1; shift
  "$sv" render --size 64x48 --no-gl --out "$tmp/bad" "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  [ $rc -eq "$want" ] || err "render $* exited $rc, expected $want: $(cat "$tmp/err")"
  [ $rc -eq 0 ] || [ -s "$tmp/err" ] || err "render $* printed no message"
  [ $rc -lt 126 ] || err "render $* crashed ($rc)"
}
expect 2 --size 0x10
expect 2 --size 8193x100
expect 2 --size 640
expect 2 --size 8192x8193
expect 2 --mode sideways
expect 2 --stencil sideways
grep -q -- '--stencil needs bf' "$tmp/err" || err "--stencil sideways: the message does not list the methods: $(cat "$tmp/err")"
expect 2 --stencil
for t in 0 7 64 -8 8x 1e1; do
  expect 2 --stencil-tile "$t"
  grep -q -- '--stencil-tile needs 4, 8, 16 or 32' "$tmp/err" || err "--stencil-tile $t: the message does not list the sides: $(cat "$tmp/err")"
done
expect 2 --stencil-tile
expect 2 --caster-rule sideways
grep -q -- '--caster-rule needs auto, closed or general' "$tmp/err" || err "--caster-rule sideways: the message does not list the rules: $(cat "$tmp/err")"
expect 2 --ground-hints sideways
grep -q -- '--ground-hints needs use or ignore' "$tmp/err" || err "--ground-hints sideways: the message does not list the choices: $(cat "$tmp/err")"
expect 2 --general-build sideways
grep -q -- '--general-build needs two-sided or direct' "$tmp/err" || err "--general-build sideways: the message does not list the builds: $(cat "$tmp/err")"
expect 2 --light point:nan,1,1
expect 2 --light point:1,inf,1
expect 2 --light point:1e39,5,0
expect 2 --light point:0,0.001,0.5
expect 2 --light spot:0,3,0,0,-1,0,50,40
expect 2 --light dir:0,0,0
expect 2 --light torch:1,2,3
expect 2 --camera eye=0,1,2
expect 2 --camera eye=0,1,2,target=0,1,2
expect 2 --camera eye=0,1,2,target=0,0,0,fov=0
expect 2 --add "$models/character_1344.glb@1,2"
expect 2 --add "$models/character_1344.glb@0,0,0,0,-1"
expect 2 --add "$models/character_1344.glb:walk"  # an animation is scene's (issue 30)
grep -q "render draws the files at rest" "$tmp/err" || err "render --add FILE:walk: the refusal does not say why: $(cat "$tmp/err")"
expect 2 --kernels mmx
expect 2 --variant nope
expect 2 --frobnicate
expect 2 --out /proc/version/x
expect 3 --add "$tmp/missing.glb"
printf 'glTF\002\000\000\000\014\000\000\000' >"$tmp/short.glb"
expect 3 --add "$tmp/short.glb"
echo '{"asset": {"version": "2.0"}, "meshes": []}' >"$tmp/empty.gltf"
expect 3 --add "$tmp/empty.gltf"
"$sv" render --help >"$tmp/out" 2>&1 || err "render --help failed"
grep -q -- '--light spot:' "$tmp/out" || err "render --help does not describe --light"
grep -q -- '--stencil S' "$tmp/out" || err "render --help does not describe --stencil"
grep -q -- '--caster-rule R' "$tmp/out" || err "render --help does not describe --caster-rule"
grep -q -- '--general-build B' "$tmp/out" || err "render --help does not describe --general-build"
grep -q -- '--ground-hints H' "$tmp/out" || err "render --help does not describe --ground-hints"

[ $fail -eq 0 ] && echo "PASSED: render CLI"
exit $fail
