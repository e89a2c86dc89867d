#!/usr/bin/env bash
# `shadowvol inspect` and `shadowvol verify` on every model: the project's
# generated character (always) and the real characters of ../shared/models
# (when that folder exists; a visible message when it does not). Each model
# must load, print its preparation report, and pass verify (every variant,
# point, culled and directional lights); then the error paths: a missing
# file, a file that is not glTF, bad arguments.
# usage: check_models_cli.sh PATH/TO/shadowvol MODELS_DIR SHARED_MODELS_DIR [SCALE] [bundled|shared]
# (bundled: the generated character and the error paths; shared: the real
# characters alone, exit 77 when their folder is missing)
#   SCALE (default 1) divides the number of points per light, for slow
#   (sanitizer) builds.
set -u
sv="$1"; models="$2"; shared="$3"; scale="${4:-1}"; set="${5:-bundled}"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

# verify MODEL LIGHTS POINTS: must pass, and the table must show checked points.
check_model() {
  local m=$1 lights=$2 points=$(( $3 / scale ))
  [ "$points" -ge 10 ] || points=10
  local name; name=$(basename "$m")
  if ! "$sv" inspect "$m" >"$tmp/inspect" 2>"$tmp/err"; then
    err "inspect $name: $(cat "$tmp/err")"; return
  fi
  grep -qE '^surface +prims' "$tmp/inspect" || err "inspect $name: no table"
  grep -q '^shells (the caster rule under --caster-rule auto):' "$tmp/inspect" || err "inspect $name: no shells and caster rules"
  echo "== shadowvol inspect $name"; cat "$tmp/inspect"
  local t0=$SECONDS
  "$sv" verify "$m" --lights "$lights" --points "$points" --seed 7 >"$tmp/verify" 2>"$tmp/err"
  local rc=$?
  echo "== shadowvol verify $name --lights $lights --points $points ($((SECONDS - t0)) s)"
  cat "$tmp/verify"
  [ $rc -eq 0 ] || err "verify $name exited $rc: $(cat "$tmp/err")"
  grep -q '^PASSED' "$tmp/verify" || err "verify $name did not print PASSED"
  grep -qE '^[0-9]+ lights' "$tmp/verify" || err "verify $name: no summary"
}

if [ "$set" = shared ]; then
  [ -d "$shared" ] || { echo "SKIP: $shared not found: the real characters cannot be checked"; exit 77; }
  check_shared() { # name lights points
    if [ -f "$shared/$1.glb" ]; then check_model "$shared/$1.glb" "$2" "$3"
    else err "missing $shared/$1.glb"; fi
  }
  for m in RiggedFigure Fox spot_lowres RobotExpressive CesiumMan spot; do
    check_shared "$m" 16 1000
  done
  check_shared koala 8 500
  [ $fail -eq 0 ] && echo "check_models_cli: the real characters passed"
  exit $fail
fi

check_model "$models/character_1344.glb" 16 1000
# The JSON reports carry their schema.
"$sv" inspect "$models/character_1344.glb" --json - 2>/dev/null | grep -q '"schema": "shadowvol-inspect/1"' \
  || err "inspect --json - has no schema field"
"$sv" verify "$models/character_1344.glb" --lights 2 --points 20 --json "$tmp/v.json" >/dev/null 2>&1 \
  && grep -q '"schema": "shadowvol-verify/1"' "$tmp/v.json" && grep -q '"passed": true' "$tmp/v.json" \
  || err "verify --json FILE: no schema or not passed"


expect_status() { # expected-status description args...
  local want=$1; shift; local what=$1; shift
  "$sv" "$@" >"$tmp/out" 2>"$tmp/err"; local got=$?
  [ $got -eq "$want" ] || err "$what: exit $got, want $want"
  [ "$want" -eq 0 ] || [ -s "$tmp/err" ] || err "$what: no message on stderr"
}
expect_status 0 "inspect --help" inspect --help
expect_status 0 "verify --help" verify --help
expect_status 2 "inspect without a model" inspect
expect_status 2 "verify --lights 0" verify "$models/character_1344.glb" --lights 0
expect_status 2 "verify --points x" verify "$models/character_1344.glb" --points x
expect_status 2 "verify unknown variant" verify "$models/character_1344.glb" --variant nope
expect_status 2 "inspect two models" inspect a.glb b.glb
expect_status 3 "inspect a missing file" inspect "$tmp/no_such_model.glb"
grep -q "no_such_model.glb" "$tmp/err" || err "missing-file message does not name the file"
printf 'not a gltf file\n' >"$tmp/text.gltf"
expect_status 3 "inspect a text file" inspect "$tmp/text.gltf"
grep -q "text.gltf" "$tmp/err" || err "bad-file message does not name the file"
expect_status 3 "verify a missing file" verify "$tmp/no_such_model.glb"

# Hostile sizes (issue 17): the scene's triangles are estimated before
# loading and refused above --max-triangles; verify's memory estimate above
# --max-memory; both exit 3 with the numbers.
expect_status 3 "inspect above --max-triangles" inspect "$models/character_1344.glb" --max-triangles 1000
grep -q "more than the limit of 1000 triangles" "$tmp/err" || err "--max-triangles message: $(cat "$tmp/err")"
expect_status 0 "inspect at --max-triangles" inspect "$models/character_1344.glb" --max-triangles 1344
expect_status 3 "verify above --max-memory" verify "$models/character_1344.glb" --max-memory 512K
grep -q "1344 triangles in the largest surface need about 0.9 MB" "$tmp/err" || err "--max-memory message: $(cat "$tmp/err")"
expect_status 0 "verify at --max-memory" verify "$models/character_1344.glb" --max-memory 1M --lights 1 --points 10
expect_status 2 "verify --max-memory x" verify "$models/character_1344.glb" --max-memory x
# verify's third result (issue 17): a tetrahedron of 1e-45 (float's denormal
# grid) is outside the sizes verify decides: CANNOT DECIDE, exit 4, with the
# reason; never PASSED, never FAILED.
cat >"$tmp/tiny.gltf" <<'GLTF'
{"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}], "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"}, {"bufferView": 1, "componentType": 5125, "count": 12, "type": "SCALAR"}], "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48}], "buffers": [{"byteLength": 96, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAQAAAAAAAAAAAAAAAAAAAAEAAAAAAAAAAAAAAAAAAAABAAAAAAAAAAIAAAABAAAAAAAAAAEAAAADAAAAAAAAAAMAAAACAAAAAQAAAAIAAAADAAAA"}]}
GLTF
expect_status 4 "verify a 1e-45 tetrahedron" verify "$tmp/tiny.gltf" --lights 2 --points 50
grep -q "^CANNOT DECIDE: .*outside the range verify decides" "$tmp/out" || err "no CANNOT DECIDE line: $(cat "$tmp/out")"
grep -q "cannot decide" "$tmp/err" || err "no cannot-decide message on stderr"
"$sv" verify "$tmp/tiny.gltf" --lights 2 --points 50 --json - 2>/dev/null | grep -q '"verdict": "undecided"' \
  || err "verify --json: no verdict undecided"

[ $fail -eq 0 ] && echo "check_models_cli: all passed"
exit $fail
