#!/usr/bin/env bash
# `shadowvol bench --frame --quick` at a small size: exit 0, the pass table
# with every pass, the work line (rows, pixels, ticks a unit), the lighting
# pass's divider line, the two checks of the run (our drawings the same bytes,
# Mesa's picture agreeing off edges, where OSMesa is built), the PNGs, the
# JSON (shadowvol-frame-bench/1), our stencil method taken as render takes
# it (the wisdom file's, else auto; --stencil over both) and the usage
# errors (exit 2).
# usage: check_frame_bench.sh PATH/TO/shadowvol
set -u
sv="$1"
fail=0
err() { echo "FAIL: $*"; fail=1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# No user's wisdom file decides the stencil method here (the wisdom runs
# below name their own).
export SV_WISDOM="$tmp/no-wisdom"

"$sv" bench --frame --quick --size 192x108 --threads 2 --out "$tmp" --json "$tmp/f.json" \
  >"$tmp/f.txt" 2>&1 || err "--frame exited $?: $(tail -3 "$tmp/f.txt")"
grep -q "FAILED" "$tmp/f.txt" && err "--frame: a check FAILED: $(grep FAILED "$tmp/f.txt")"
for pass in "pose, skin, planes" volumes depth stencil lighting "clear, copies" frame; do
  grep -q "^$pass " "$tmp/f.txt" || err "--frame: no '$pass' row"
done
grep -q "^check: 2 of 2 frames the same bytes" "$tmp/f.txt" || err "--frame: no same-bytes check"
grep -Eq "^work a frame: depth [1-9][0-9]* triangles, .* stencil [0-9]+ volume triangles, .* rows, .* ticks a row.* lighting .* ticks a pixel and light" "$tmp/f.txt" ||
  err "--frame: no work line: $(grep '^work' "$tmp/f.txt")"
grep -Eq "^lighting's divider: [0-9.]+ M lanes .* \(divide [0-9.]+, square root [0-9.]+ ticks a lane in (2|4|8)-lane vectors, best of 5\)" "$tmp/f.txt" ||
  err "--frame: no divider line: $(grep "^lighting's" "$tmp/f.txt")"
grep -Eq "^check: Mesa .* 0 other; stencils: 0 other$" "$tmp/f.txt" || err "--frame: no Mesa check with 0 other"
[ -s "$tmp/frame_ours.png" ] && [ -s "$tmp/frame_mesa.png" ] || err "--frame: PNGs missing"
if command -v python3 >/dev/null; then
  python3 - "$tmp/f.json" <<'PY' || err "--frame: bad JSON"
import json, sys
top = json.load(open(sys.argv[1]))
assert top["schema"] == "shadowvol-frame-bench/1"
d = top["frame"]
assert d["preset"] == "demo"
assert d["width"] == 192 and d["height"] == 108 and d["threads"] == 2
assert d["frames"] == 2 and d["runs_per_frame"] == 1, d
names = [p["pass"] for p in d["passes"]]
assert names == ["pose, skin, planes", "volumes", "depth", "stencil", "lighting",
                 "clear, copies", "frame"], names
for p in d["passes"]:
    assert p["ours_ms"] >= 0, p
for p in d["passes"][2:5] + d["passes"][6:]:
    assert p["floor_ms"] > 0 and p["mesa_ms"] > 0, p
m = d["mesa"]
assert m["lp_num_threads"] == 2 and m["runs_per_frame"] == 1, m
assert m["other"] == 0 and m["stencil_other"] == 0, m
assert m["equal"] + m["on_edge"] == m["compared"] > 0, m
w = d["work_per_frame"]
assert w["depth_triangles"] > 0 and w["depth_rows"] > 0 and w["depth_pixels_tested"] > 0, w
assert w["stencil_rows"] > 0 and w["stencil_pixels_tested"] > 0, w
assert w["pixels"] == 192 * 108 and w["lights"] >= 1, w
assert d["tsc_hz"] > 0
assert w["visible_pixels"] > 0 and w["divider_lanes"] >= 0, w
dv = d["divider"]
assert dv["div_ticks_per_lane"] > 0 and dv["sqrt_ticks_per_lane"] > 0 and dv["lanes"] in (2, 4, 8), dv
assert d["same_bytes_every_run"] is True and d["ok"] is True
# Without a wisdom file or --stencil: auto at its offline threshold.
assert d["stencil"] == "auto" and d["stencil_source"] == "default", d["stencil"]
assert d["stencil_tile"] == 32 and d["stencil_hier_from_area_per_piece"] == 65, d
PY
else
  err "python3 not found: the JSON's fields cannot be checked (tools/run.sh test installs it)"
fi
# A wisdom line for this CPU sets the method, tile and threshold; --stencil
# overrides the method and keeps the rest (render_cli's rule).
cpu=$("$sv" tune --class 0 --no-stencil --dry-run 2>/dev/null | sed -n 's/^cpu  *//p')
[ -n "$cpu" ] || err "tune printed no cpu line"
printf 'shadowvol-wisdom 1\ncpu %s\nstencil hier 16 40.0\n' "$cpu" >"$tmp/wisdom"
wisdom_frame() { # EXPECTED_METHOD EXPECTED_SOURCE ARGS...
  local method=$1 source=$2; shift 2
  SV_WISDOM="$tmp/wisdom" "$sv" bench --frame --quick --size 64x36 --threads 1 --no-mesa \
    --json "$tmp/w.json" "$@" >"$tmp/w.txt" 2>&1 || err "--frame $* with a wisdom file exited $?"
  grep -q "our stencil pass: $method ($source; tile 16, auto's hier from 40.0 pixels a piece)" \
    "$tmp/w.txt" || err "--frame $*: not $method from $source: $(grep 'our stencil' "$tmp/w.txt")"
  grep -q "\"stencil\": \"$method\"" "$tmp/w.json" && grep -q "\"stencil_source\": \"$source\"" "$tmp/w.json" \
    && grep -q '"stencil_tile": 16' "$tmp/w.json" || err "--frame $*: the JSON does not say $method from $source"
}
wisdom_frame hier wisdom
wisdom_frame bf option --stencil bf
for args in "--frame --scene" "--frame=1" "--frame --size 0x10" "--frame --threads 0" \
            "--frame --model x.glb" "--threads 2" "--frame --out" "--frame --caster-rule auto"; do
  # shellcheck disable=SC2086
  "$sv" bench $args >"$tmp/u.txt" 2>&1
  rc=$?
  [ "$rc" = 2 ] || err "bench $args: exit $rc, expected 2"
done
"$sv" bench --frame --preset no_such_file.glb --size 64x36 --no-mesa >"$tmp/u.txt" 2>&1
rc=$?
[ "$rc" = 3 ] || err "bench --frame --preset no_such_file.glb: exit $rc, expected 3"
[ "$fail" = 0 ] && echo "bench --frame: all checks passed"
exit "$fail"
