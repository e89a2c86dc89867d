#!/usr/bin/env bash
# `shadowvol bench --silhouette` and `--backface` (seeds 003 and 001) on the
# smaller meshes: exit 0, every row checked and present in the table and in
# the JSON (shadowvol-silhouette/1, shadowvol-backface/1, field by field when
# python3 is there), and the usage errors (exit 2).
# usage: check_seed_bench.sh PATH/TO/shadowvol [MAX_TRIANGLES]
set -u
sv="$1"; max="${2:-15000}"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$sv" bench --silhouette --quick --max-triangles "$max" --json "$tmp/s.json" >"$tmp/s.txt" 2>&1 \
  || err "--silhouette exited $?: $(tail -3 "$tmp/s.txt")"
for v in siledge_c_ref classic hash8_u16 hash64_u16 hash8_u32 hash64_u32 hash8_u16_sse2 \
         hash64_u32_sse2 connectivity connectivity_branchless; do
  grep -q "^    $v " "$tmp/s.txt" || err "--silhouette: no row $v"
done
grep -q "FAILED" "$tmp/s.txt" && err "--silhouette: a FAILED row"
grep -q "Dino (28766 faces), seed" "$tmp/s.txt" || err "--silhouette: no seed table"

"$sv" bench --backface --quick --max-triangles "$max" --json "$tmp/b.json" >"$tmp/b.txt" 2>&1 \
  || err "--backface exited $?: $(tail -3 "$tmp/b.txt")"
grep -q "FAILED" "$tmp/b.txt" && err "--backface: a FAILED row"
grep -q "^character_1344 " "$tmp/b.txt" || err "--backface: no 1344-triangle row"

if command -v python3 >/dev/null 2>&1; then
  python3 - "$tmp/s.json" "$tmp/b.json" <<'PY' || err "JSON field check failed"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["schema"] == "shadowvol-silhouette/1" and s["routine"] == "find_silhouette"
assert [m["model"] for m in s["seed_003"]] == ["Dino", "Dragon"]
assert len(s["meshes"]) >= 1
for m in s["meshes"]:
    assert m["tables_agree"] is True
    assert m["connectivity_linear_ms"] >= 0
    assert {p["light"] for p in m["placements"]} == {"above", "beside"}
    for p in m["placements"]:
        names = [r["variant"] for r in p["rows"]]
        assert "classic" in names and "connectivity" in names and "siledge_c_ref" in names
        assert sum(n.startswith("hash") for n in names) == 16, names
        for r in p["rows"]:
            assert r["routine"] == "find_silhouette"
            assert r["status"] in ("ok", "overflow"), r
            assert r["ok"] is True
            if r["status"] == "ok":
                assert r["calls"] >= 2 and r["median_ticks"] >= r["min_ticks"] >= 0
            assert r["temporary_bytes"] >= 0 and r["permanent_bytes"] >= 0
            if r["variant"].startswith("hash"):
                assert r["temporary_bytes"] > 0
            if r["variant"].startswith("connectivity"):
                assert r["permanent_bytes"] == 4 * 3 * m["triangles"] + 4 * m["dangling"]
                assert r["precompute_ms"] is not None
b = json.load(open(sys.argv[2]))
assert b["schema"] == "shadowvol-backface/1" and b["routine"] == "backface_cull"
for sz in b["sizes"]:
    names = {(r["variant"], r["vertex_bits"]) for r in sz["rows"]}
    for v in ("noncompact", "compact", "compact_sse2", "compact_sse2_prefetch"):
        assert (v, True) in names and (v, False) in names, v
    for r in sz["rows"]:
        assert r["ok"] is True and r["calls"] >= 2, r
    assert sz["differ_within_fixed16_bound"] + sz["differ_float_wrong"] == sz["compact_vs_noncompact_differ"]
    assert 0 < sz["front_ratio"] < 1
print("JSON: %d silhouette meshes, %d back-face sizes checked" % (len(s["meshes"]), len(b["sizes"])))
PY
else
  err "python3 not found: the JSON's fields cannot be checked (tools/run.sh test installs it)"
fi

# Usage errors: exit 2.
for args in "--silhouette --model x.glb" "--backface --silhouette" "--silhouette=1" \
            "--backface --variant c_ref" "--backface --scaling" "--silhouette --runs 5"; do
  "$sv" bench $args >"$tmp/e.txt" 2>&1
  rc=$?
  [ "$rc" = 2 ] || err "bench $args: exit $rc, not 2"
done

[ "$fail" = 0 ] && echo "seed benchmarks: ok"
exit "$fail"
