#!/usr/bin/env bash
# `shadowvol bench --planes --quick`: exit 0, no FAILED row, the derive
# table with a row per mesh and a column per variant this CPU runs, the
# frame table, the JSON (shadowvol-planes/1, every row ok, when python3 is
# there), and the usage errors (exit 2).
# usage: check_planes_bench.sh PATH/TO/shadowvol
set -u
sv="$1"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$sv" bench --planes --quick --json "$tmp/p.json" >"$tmp/p.txt" 2>&1 \
  || err "--planes exited $?: $(tail -3 "$tmp/p.txt")"
grep -Eq "(^FAILED| FAIL( |$))" "$tmp/p.txt" && err "--planes: a FAILED row"
grep -q "^derive planes, ticks per triangle" "$tmp/p.txt" || err "--planes: no derive table"
grep -q "^facing for a frame of 1 and 4 moving lights" "$tmp/p.txt" || err "--planes: no frame table"
grep -Eq "^mesh +triangles +c_ref +sse2" "$tmp/p.txt" || err "--planes: no variant columns"
# The floor (the planes' arithmetic on corners gathered beforehand) runs
# wherever AVX2 does, checked bit for bit like the kernels.
if grep -Eq "^isa .* avx2( |$)" "$tmp/p.txt"; then
  grep -Eq "^mesh +triangles .* floor_avx2 " "$tmp/p.txt" || err "--planes: no floor_avx2 column"
fi
[ "$(grep -c '^character_1344.glb ' "$tmp/p.txt")" -ge 3 ] || err "--planes: character rows missing"
[ "$(grep -c '^grid_8192 ' "$tmp/p.txt")" -ge 3 ] || err "--planes: grid rows missing"
# The crossover table: the demo scene's character at 1 to 4 lights, each
# with derived, bfg and their ratio (a number), and the light count from
# which deriving pays (1-4, or - when not up to 4).
grep -q "^lights per frame: the per-light job" "$tmp/p.txt" || err "--planes: no crossover table"
grep -Eq '^demo_scene.glb +[0-9]+( +[0-9.]+ +[0-9.]+ +[0-9]+\.[0-9]+){4} +([1-4]|-)$' "$tmp/p.txt" \
  || err "--planes: no crossover row for the demo scene"
if command -v python3 >/dev/null; then
  python3 - "$tmp/p.json" <<'PY' || err "--planes: bad JSON"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["schema"] == "shadowvol-planes/1"
assert len(d["meshes"]) == 2, d["meshes"]
for m in d["meshes"]:
    whats = {r["routine"] for r in m["rows"]}
    assert whats == {"derive", "cluster_build", "bfg_1", "bfg_4", "planes_1", "planes_4"}, whats
    assert any(r["variant"] == "clusters_c_ref" for r in m["rows"] if r["routine"] == "derive")
    assert m["clusters"] > 0, m["clusters"]
    for r in m["rows"]:
        assert r["ok"] is True and r["calls"] > 0 and r["ticks_per_triangle"] > 0, r
    assert 0 <= m["bfg_vs_planes_facing_differ"] <= m["facing_compared"]
for c in d["skinned"]:
    jobs = {r["routine"] for r in c["rows"] if r["routine"].startswith("job_")}
    for k in "1234":
        assert {"job_derived_" + k, "job_bfg_" + k} <= jobs, (c["character"], jobs)
    for r in c["rows"]:
        assert r["ok"] is True and r["ticks_per_triangle"] > 0, r
PY
else
  err "python3 not found: the JSON's fields cannot be checked (tools/run.sh test installs it)"
fi
for args in "--planes --backface" "--planes=1" "--planes --variant c_ref" "--planes --model x.glb"; do
  # shellcheck disable=SC2086
  "$sv" bench $args >"$tmp/u.txt" 2>&1
  rc=$?
  [ "$rc" = 2 ] || err "bench $args: exit $rc, expected 2"
done
[ "$fail" = 0 ] && echo "bench --planes: all checks passed"
exit "$fail"
