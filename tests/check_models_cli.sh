#!/usr/bin/env bash
# `shadowvol inspect` and `shadowvol verify` on every model: the project's
# generated character (always) and the real characters of ../shared/models
# (when that folder exists; a visible message when it does not). Each model
# must load, print its preparation report, and pass verify (every variant,
# point, culled and directional lights); then the error paths: a missing
# file, a file that is not glTF, bad arguments.
# usage: check_models_cli.sh PATH/TO/shadowvol MODELS_DIR SHARED_MODELS_DIR [SCALE]
#   SCALE (default 1) divides the number of points per light, for slow
#   (sanitizer) builds.
set -u
sv="$1"; models="$2"; shared="$3"; scale="${4:-1}"
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

check_model "$models/character_1344.glb" 16 1000
# The JSON reports carry their schema.
"$sv" inspect "$models/character_1344.glb" --json - 2>/dev/null | grep -q '"schema": "shadowvol-inspect/1"' \
  || err "inspect --json - has no schema field"
"$sv" verify "$models/character_1344.glb" --lights 2 --points 20 --json "$tmp/v.json" >/dev/null 2>&1 \
  && grep -q '"schema": "shadowvol-verify/1"' "$tmp/v.json" && grep -q '"passed": true' "$tmp/v.json" \
  || err "verify --json FILE: no schema or not passed"

if [ -d "$shared" ]; then
  check_shared() { # name lights points
    if [ -f "$shared/$1.glb" ]; then check_model "$shared/$1.glb" "$2" "$3"
    else err "missing $shared/$1.glb"; fi
  }
  for m in RiggedFigure Fox spot_lowres RobotExpressive CesiumMan spot; do
    check_shared "$m" 16 1000
  done
  check_shared koala 8 500
else
  echo "NOTE: $shared not found: the real characters were NOT checked (only the generated one)."
fi

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

[ $fail -eq 0 ] && echo "check_models_cli: all passed"
exit $fail
