#!/usr/bin/env bash
# `shadowvol accuracy`: --help; the --quick run within its time budget, its
# table, its shadowvol-accuracy/1 JSON (every variant x light placement row
# once, with the fields the schema promises; checked field by field when
# python3 is there) and its SVG plot; --model/--variant/--placement
# narrowing; JSON on stdout; the error exits (2 bad arguments, 3 a model
# that cannot be loaded or a file that cannot be written).
# usage: check_accuracy_cli.sh PATH/TO/shadowvol MODELS_DIR [QUICK_SECONDS]
#   QUICK_SECONDS (default 10): the --quick run's budget; sanitizer builds
#   pass a larger one.
set -u
sv="$1"; models="$2"; budget="${3:-10}"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

if ! "$sv" accuracy --help >"$tmp/help" 2>&1; then
  echo "FAIL: '$sv accuracy --help' failed: $(head -1 "$tmp/help")"
  echo "      (the accuracy subcommand is registered in src/cli/main.cpp)"
  exit 1
fi
for word in --quick --json --plot --model exact fixed16 eps_bias graze 1e6r; do
  grep -q -- "$word" "$tmp/help" || err "--help does not mention $word"
done

# The quick run.
t0=$(date +%s%N)
"$sv" accuracy --quick --json "$tmp/a.json" --plot "$tmp/a.svg" >"$tmp/out" 2>"$tmp/err"
rc=$?
ms=$(( ($(date +%s%N) - t0) / 1000000 ))
echo "== shadowvol accuracy --quick ($ms ms)"; cat "$tmp/out"
[ $rc -eq 0 ] || err "--quick exited $rc: $(cat "$tmp/err")"
[ "$ms" -le $(( budget * 1000 )) ] || err "--quick took $ms ms (budget $budget s)"
grep -q '^PASSED' "$tmp/out" || err "--quick did not print PASSED"
grep -q '^character_1344.glb: 1 surface, 1344 triangles' "$tmp/out" || err "no model line"
grep -qE '^variant +ticks/tri +graze +hair +inside +2r +10r +100r +1e4r +1e6r +dir +axis' \
  "$tmp/out" || err "no per-placement table"
grep -qE '^models: ' "$tmp/out" || err "no line saying which models were measured"
grep -qE '^exact +[0-9.]+ +0 +0 ' "$tmp/out" || err "the exact row is not all zeros"

# JSON: the schema, one row per variant x placement.
grep -q '"schema": "shadowvol-accuracy/1"' "$tmp/a.json" || err "JSON: no schema"
rows=$(grep -o '{"variant": ' "$tmp/a.json" | wc -l)
echo "JSON rows: $rows"
[ "$rows" -ge 100 ] || err "JSON: only $rows rows"
if command -v python3 >/dev/null 2>&1; then
  python3 - "$tmp/a.json" <<'EOF' || err "JSON: field check failed"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["schema"] == "shadowvol-accuracy/1"
assert d["passed"] is True and d["failures"] == []
variants = [v["name"] for v in d["variants"]]
for must in ("c_ref", "fma", "double", "fixed16", "eps_bias", "exact"):
    assert must in variants, must
placements = {"graze", "hair", "inside", "2r", "10r", "100r", "1e4r", "1e6r", "dir", "axis"}
seen = set()
for r in d["results"]:
    key = (r["variant"], r["model"], r["light"]["placement"])
    assert key not in seen, key
    seen.add(key)
    assert r["model"] == "character_1344.glb"
    assert r["triangles"] == 1344 and r["tests"] == 1344 * r["light"]["count"]
    assert r["light"]["kind"] in ("point", "directional")
    if r["light"]["kind"] == "directional":
        assert r["light"]["distance_radii"] is None
    else:
        assert r["light"]["distance_radii"] > 0
    for f in ("misclassified_fraction", "silhouette_changed_fraction", "uncertain_fraction",
              "flicker_fraction"):
        assert 0.0 <= r[f] <= 1.0, (key, f)
    # >= 0, not > 0: the empty region is subtracted, and on a busy machine a
    # fast variant's median can come out at 0 (clamped). No timing asserts.
    assert r["ticks_per_triangle"] >= 0, key
    assert r["contract_violations"] == 0
    if r["variant"].startswith("exact"):
        assert r["misclassified"] == 0 and r["silhouette_changed"] == 0
assert {k[2] for k in seen} == placements, {k[2] for k in seen}
assert len(seen) == len(variants) * len(placements)
print("JSON: %d rows checked field by field" % len(seen))
EOF
else
  err "python3 not found: the JSON's fields cannot be checked (tools/run.sh test installs it)"
fi

# The plot: an SVG document with a point label per variant.
head -c 5 "$tmp/a.svg" | grep -q '<?xml' || err "plot: not an XML document"
grep -q '</svg>' "$tmp/a.svg" || err "plot: not closed"
for v in c_ref fma_avx2 double fixed16_avx2 eps_bias exact; do
  grep -q ">$v<" "$tmp/a.svg" || err "plot: no point labelled $v"
done

# Narrowed: one model, two variants, one placement, no timing; JSON on
# stdout (the tables then go to stderr).
"$sv" accuracy --model "$models/character_1344.glb" --variant c_ref --variant exact \
  --placement dir --lights 2 --no-timing --json - >"$tmp/n.json" 2>"$tmp/n.err" \
  || err "narrowed run exited $?: $(cat "$tmp/n.err")"
[ "$(grep -o '{"variant": ' "$tmp/n.json" | wc -l)" = 2 ] || err "narrowed run: not 2 rows"
grep -q '"ticks_per_triangle": null' "$tmp/n.json" || err "--no-timing: ticks not null"
grep -q '^PASSED' "$tmp/n.err" || err "JSON on stdout: the table did not go to stderr"

expect_status() { # expected-status description args...
  local want=$1; shift; local what=$1; shift
  "$sv" accuracy "$@" >"$tmp/out" 2>"$tmp/err"; local got=$?
  [ "$got" = "$want" ] || err "$what: exit $got, want $want"
  [ "$want" = 0 ] || [ -s "$tmp/err" ] || err "$what: no message on stderr"
}
expect_status 2 "unknown option" --frobnicate
expect_status 2 "--lights 0" --lights 0
expect_status 2 "unknown variant" --variant nope
expect_status 2 "unknown placement" --placement nowhere
expect_status 2 "stray argument" model.glb
expect_status 3 "missing model" --model "$tmp/missing.glb" --no-timing
echo "not a model" >"$tmp/bad.glb"
expect_status 3 "not glTF" --model "$tmp/bad.glb" --no-timing
expect_status 3 "unwritable JSON" --model "$models/character_1344.glb" --placement dir \
  --lights 1 --no-timing --json "$tmp/no/such/dir/a.json"

exit $fail
