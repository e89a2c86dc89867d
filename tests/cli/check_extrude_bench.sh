#!/usr/bin/env bash
# `shadowvol bench --extrude --quick`: exit 0, no FAILED row, the per-vertex
# table with a column per variant this CPU runs, the table against the
# paper's pipeline, the counts (GenShadowMesh's for the closed character:
# 3F vertices, 12F indices), the skinned normal sources' time and bytes,
# the JSON (shadowvol-extrude/1, every row ok,
# when python3 is there), and the usage errors (exit 2).
# usage: check_extrude_bench.sh PATH/TO/shadowvol
set -u
sv="$1"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$sv" bench --extrude --quick --json "$tmp/e.json" >"$tmp/e.txt" 2>&1 \
  || err "--extrude exited $?: $(tail -3 "$tmp/e.txt")"
grep -Eq "(^FAILED| FAIL( |$))" "$tmp/e.txt" && err "--extrude: a FAILED row"
grep -q "^seed 002's vertex program on the CPU, ticks per vertex" "$tmp/e.txt" \
  || err "--extrude: no per-vertex table"
grep -q "^one light, ticks per call" "$tmp/e.txt" || err "--extrude: no table against the paper"
grep -Eq "^mesh +vertices +c_ref" "$tmp/e.txt" || err "--extrude: no variant columns"
[ "$(grep -c '^character_1344.glb ' "$tmp/e.txt")" -ge 3 ] || err "--extrude: character rows missing"
grep -q "^the skinned normal sources" "$tmp/e.txt" || err "--extrude: no skinned normal sources' table"
grep -q "^the bytes a shadow-mesh vertex carries" "$tmp/e.txt" || err "--extrude: no bytes table"
if command -v python3 >/dev/null; then
  python3 - "$tmp/e.json" <<'PY' || err "--extrude: bad JSON"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["schema"] == "shadowvol-extrude/1"
assert len(d["meshes"]) == 1, d["meshes"]
m = d["meshes"][0]
f = m["faces"]
assert m["seed_vertices"] == 3 * f and m["seed_indices"] == 12 * f, m
whats = {r["routine"] for r in m["rows"]}
assert whats == {"extrude_range", "extrude_inf", "paper"}, whats
for r in m["rows"]:
    assert r["ok"] is True and r["calls"] > 0 and r["median_ticks"] > 0, r
assert 0 < m["paper_indices_mean"] < m["seed_indices"], m
# The skinned normal sources (--quick: the demo scene's character): every
# row timed and checked, the neighbour fix splitting no face, and its
# vertex three times the straightforward one's position data (a position
# and its skin) with no normal.
sk = d["skinned"]
assert [c["character"] for c in sk] == ["demo_scene.glb"], sk
c = sk[0]
assert c["shadow_vertices"] == 3 * c["faces"] > 0, c
whats = {r["routine"] for r in c["rows"]}
assert whats == {"skinned_program", "skinned_straightforward", "skinned_face_weights",
                 "skinned_recomputed", "skinned_neighbours"}, whats
for r in c["rows"]:
    assert r["ok"] is True and r["calls"] > 0 and r["median_ticks"] > 0, r
assert c["neighbours_split_faces"] == 0, c
b = c["bytes_per_vertex"]
assert b["recomputed"] == 24 and b["straightforward"] > 24, b
assert b["face_weights"] > b["straightforward"], b
assert abs(b["neighbours"] - 3 * (b["straightforward"] - 12)) < 1e-9, b
PY
else
  err "python3 not found: the JSON's fields cannot be checked (tools/run.sh test installs it)"
fi
for args in "--extrude --planes" "--extrude=1" "--extrude --variant c_ref" "--extrude --model x.glb"; do
  # shellcheck disable=SC2086
  "$sv" bench $args >"$tmp/u.txt" 2>&1
  rc=$?
  [ "$rc" = 2 ] || err "bench $args: exit $rc, expected 2"
done
[ "$fail" = 0 ] && echo "bench --extrude: all checks passed"
exit "$fail"
