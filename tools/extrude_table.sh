#!/usr/bin/env bash
# What seed 002 trades (issue 31), per model and light: the seed's volume
# (--volume extrude: the shadow mesh through its vertex program on the CPU,
# drawn whole in z-fail with its saturating stencil) against the paper's
# (silhouette and caps, --mode zfail), one light per render:
#   faces    the caster's triangles (an open model's shells two-sided by
#            the general rule: the seed's mesh is built from those)
#   vtx      vertices transformed per light: the seed's 3F, the paper's 2V
#            (its double-length shadow vertex buffer)
#   idx      indices drawn: the seed's whole static list, the paper's
#            silhouette and caps for the light
#   set-up   volume triangles submitted to the rasteriser's set-up / of
#            them rejected as zero-area after snapping (the seed's
#            degenerate quads in view; outside the view they are rejected
#            before, and counted in "outside" of the JSON)
#   px       stencil pixels tested (covered) by the volume triangles
#   tk       CPU ticks for the light's volumes: the seed's vertex program
#            (sv_best_extrude_variant) against the paper's facing, culling
#            and volume routines, the minimum over REPEATS renders (one
#            cold frame each: see tools/caster_table.sh's caveat)
#   sat      stencil pixels where the seed's saturating count and the
#            wrap-around count differ (0: saturation changed nothing)
#   truth    the seed's pixels wrong against the ray truth off the shadow
#            boundary (the proof: 0)
# bench --extrude times the CPU side warm, call by call (docs/EXTRUSION.md).
#
# usage: tools/extrude_table.sh [BUILD_DIR] [--size WxH] [--repeats N] [MODEL...]
# (default: the bundled character, every *.glb of ../shared/models and of
# ../shared/models/open, 640x480, 3 repeats; lights point:auto (no range),
# spot:auto, dir:auto)
set -u
repo=$(cd "$(dirname "$0")/.." && pwd)
# shellcheck source=tools/table_args.sh
. "$repo/tools/table_args.sh"
build="$repo/build" size=640x480 repeats=3
table_args extrude_table 30 "--size --repeats" -- "$@"
[ -x "$sv" ] || { echo "extrude_table: no $sv (build first)" >&2; exit 2; }
table_default_models
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT

printf '%-20s %-5s %7s | %8s %8s | %8s %8s | %13s %13s | %8s %8s | %9s %9s | %6s %5s\n' \
  model light faces "vtx seed" "paper" "idx seed" "paper" "set-up seed" "paper" "px seed" "paper" \
  "tk seed" "paper" "sat" truth
status=0
for m in "${models[@]}"; do
  name=$(basename "$m")
  for light in point:auto spot:auto dir:auto; do
    common=(--add "$m" --ground --light "$light" --size "$size" --threads 1 --no-gl)
    for r in $(seq 1 "$repeats"); do
      "$sv" render "${common[@]}" --volume extrude --json "$work/seed$r.json" --out "$work/seed" \
        >/dev/null 2>&1 || status=1
      "$sv" render "${common[@]}" --mode zfail --no-truth --json "$work/paper$r.json" \
        --out "$work/paper" >/dev/null 2>&1 || status=1
    done
    "$sv" render "${common[@]}" --volume extrude --stencil-op wrap --no-truth \
      --json "$work/wrap.json" --out "$work/wrap" >/dev/null 2>&1 || status=1
    python3 - "$name" "${light%%:*}" "$work" "$repeats" <<'PY' || status=1
import json, sys, zlib, struct
name, light, work, repeats = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
def load(p): return json.load(open(p))
seed = [load(f"{work}/seed{r}.json") for r in range(1, repeats + 1)]
paper = [load(f"{work}/paper{r}.json") for r in range(1, repeats + 1)]
s, p = seed[0]["lights"][0], paper[0]["lights"][0]
model = [x for x in seed[0]["surfaces"] if not x["ground"]]
faces = sum(x["triangles"] for x in model)
verts = sum(x["vertices"] for x in model)
def png_pixels(path):
    data = open(path, "rb").read()
    pos, idat, w, h = 8, b"", 0, 0
    while pos < len(data):
        n, t = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if t == b"IHDR": w, h = struct.unpack(">II", body[:8])
        if t == b"IDAT": idat += body
        pos += 12 + n
    return zlib.decompress(idat), w, h
a, w, h = png_pixels(f"{work}/seed/stencil.png")
b, _, _ = png_pixels(f"{work}/wrap/stencil.png")
stride = (len(a) // h)
differ = sum(1 for y in range(h) if a[y*stride:(y+1)*stride] != b[y*stride:(y+1)*stride])
px_differ = 0
if differ:
    bpp = (stride - 1) // w
    for y in range(h):
        ra, rb = a[y*stride+1:(y+1)*stride], b[y*stride+1:(y+1)*stride]
        px_differ += sum(1 for x in range(w) if ra[x*bpp:(x+1)*bpp] != rb[x*bpp:(x+1)*bpp])
def ticks(js, keys):
    return min(sum(j["lights"][0]["ticks"].get(k, 0) for k in keys) for j in js)
# The seed's vertices: 3 per face of each drawn shadow mesh, whose static
# list holds 3 indices per face and 6 per paired edge, 12F for a closed
# mesh (an open model's shells are two-sided first, so closed too).
seed_idx = s["drawn_indices"]
seed_vtx = sum(l["indices"] for l in s["index_lists"]) // 4
sc, pc = s["stencil_counters"], p["stencil_counters"]
truth = s.get("truth", {}).get("off_boundary_mismatches", "-")
print(f"{name[:20]:<20} {light:<5} {faces:7d} | {seed_vtx:8d} {2*verts:8d} | "
      f"{seed_idx:8d} {p['drawn_indices']:8d} | {sc['triangles']:6d}/{sc['degenerate']:6d} "
      f"{pc['triangles']:6d}/{pc['degenerate']:6d} | {sc['pixels_tested']:8d} {pc['pixels_tested']:8d} | "
      f"{ticks(seed, ['extrude']):9d} {ticks(paper, ['facing', 'culling', 'volume']):9d} | "
      f"{px_differ:6d} {truth!s:>5}")
PY
  done
done
echo
echo "command: tools/extrude_table.sh ${size:+--size $size} --repeats $repeats"
exit $status
