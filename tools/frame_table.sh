#!/usr/bin/env bash
# Issue 29's table: `shadowvol bench --frame` once per thread count, each
# in a process of its own (llvmpipe reads LP_NUM_THREADS once per
# process), a preset (default the demo scene) at --size, our stencil pass
# by --stencil's method (default: the planner's choice, as render takes
# it: the wisdom file's, else auto), and one line per (threads, pass):
# ours, its floor, Mesa's, from each run's JSON, which records the method
# and where it came from.
#
#   tools/frame_table.sh [BUILD_DIR] [--size WxH] [--threads "1 2"] [--frames N] [--runs N]
#                        [--preset P] [--stencil bf|db|hier|auto] [--out DIR]
#
# BUILD_DIR default build; --out keeps each run's JSON and text there.
# Needs python3 (tools/packages.txt, job test).
set -euo pipefail
build=build size=1280x720 threads="1 2" frames=8 runs=3 out="" preset=demo stencil=
while [ $# -gt 0 ]; do
  case "$1" in
    --size) size="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --preset) preset="$2"; shift 2 ;;
    --stencil) stencil="$2"; shift 2 ;;
    -*) echo "tools/frame_table.sh: unknown option $1" >&2; exit 2 ;;
    *) build="$1"; shift ;;
  esac
done
sv="$build/shadowvol"
[ -x "$sv" ] || { echo "tools/frame_table.sh: no $sv (build first)" >&2; exit 2; }
dir="${out:-$(mktemp -d)}"
mkdir -p "$dir"
for t in $threads; do
  "$sv" bench --frame --preset "$preset" --size "$size" --threads "$t" ${stencil:+--stencil "$stencil"} \
    --frames "$frames" --runs "$runs" \
    --json "$dir/frame_$t.json" >"$dir/frame_$t.txt" 2>&1 || {
    echo "tools/frame_table.sh: bench --frame --threads $t failed:" >&2
    tail -5 "$dir/frame_$t.txt" >&2
    exit 1
  }
done
python3 - "$dir" $threads <<'PY'
import json, sys
d, counts = sys.argv[1], sys.argv[2:]
print(f"{'threads':>7} {'pass':<20} {'ours ms':>9} {'floor ms':>9} {'/floor':>7} {'Mesa ms':>9} {'Mesa/us':>8}")
for t in counts:
    j = json.load(open(f"{d}/frame_{t}.json"))["frame"]
    print(f"{t:>7} our stencil pass: {j['stencil']} ({j['stencil_source']}; tile "
          f"{j['stencil_tile']}, auto's hier from {j['stencil_hier_from_area_per_piece']} "
          f"pixels a piece)")
    for p in j["passes"]:
        fl = p.get("floor_ms"); me = p.get("mesa_ms")
        print(f"{t:>7} {p['pass']:<20} {p['ours_ms']:9.2f} "
              + (f"{fl:9.2f} {p['ours_ms'] / fl:7.1f} " if fl else f"{'-':>9} {'-':>7} ")
              + (f"{me:9.2f} {me / p['ours_ms']:8.2f}" if me else f"{'-':>9} {'-':>8}"))
    m = j["mesa"]
    print(f"{'':>7} checks: same bytes every run {j['same_bytes_every_run']}; Mesa "
          f"(LP_NUM_THREADS {m['lp_num_threads']}) {m['equal']} equal, {m['on_edge']} on an edge, "
          f"{m['other']} other, stencils {m['stencil_other']} other; "
          f"memory {j['memory_read_gbps']:.1f}/{j['memory_write_gbps']:.1f} GB/s")
PY
