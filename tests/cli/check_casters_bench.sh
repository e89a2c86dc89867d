#!/usr/bin/env bash
# `shadowvol bench --casters` (issue 27): exit 0, no FAILED row, the table
# with the generated open cases and the demo terrain (the open character
# too where ../shared/models is), and the JSON (shadowvol-casters-bench/1)
# with the four pipelines per row, their counts and indices; the usage
# errors (exit 2).
# usage: check_casters_bench.sh PATH/TO/shadowvol
set -u
sv="$1"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$sv" bench --casters --quick --json "$tmp/c.json" >"$tmp/c.txt" 2>&1 \
  || err "--casters exited $?: $(tail -3 "$tmp/c.txt")"
grep -q "FAILED" "$tmp/c.txt" && err "--casters: a FAILED row: $(grep FAILED "$tmp/c.txt" | head -3)"
grep -q "direct/paper" "$tmp/c.txt" || err "--casters: no table header"
for m in "one triangle" "cylinder open at one end" "4 triangles on one edge" "demo terrain"; do
  grep -q "^$m " "$tmp/c.txt" || err "--casters: no row for $m"
done

if command -v python3 >/dev/null 2>&1; then
  python3 - "$tmp/c.json" <<'PY' || err "JSON field check failed"
import json, sys
c = json.load(open(sys.argv[1]))
assert c["schema"] == "shadowvol-casters-bench/1"
assert c["variants"]["general"]
assert len(c["rows"]) >= 20
for r in c["rows"]:
    assert r["mode"] in ("zpass", "zfail") and r["triangles"] >= 1
    names = [p["variant"] for p in r["pipelines"]]
    assert names == ["paper", "two-sided", "direct", "direct c"], names
    for p in r["pipelines"]:
        assert p["ok"] is True, p
        assert p["calls"] >= 2 and p["median_ticks"] >= p["min_ticks"] >= 0
        assert p["indices"] >= 0 and p["indices"] % 3 == 0
    # direct and its C reference build the same list
    assert r["pipelines"][2]["indices"] == r["pipelines"][3]["indices"]
PY
fi

"$sv" bench --casters --caster-rule auto >"$tmp/out" 2>&1
[ $? -eq 2 ] || err "bench --casters --caster-rule: not a usage error"
"$sv" bench --casters --scene >"$tmp/out" 2>&1
[ $? -eq 2 ] || err "bench --casters --scene: not a usage error"
"$sv" bench --casters=1 >"$tmp/out" 2>&1
[ $? -eq 2 ] || err "bench --casters=1: not a usage error"

[ $fail -eq 0 ] && echo "PASSED: bench --casters"
exit $fail
