#!/usr/bin/env bash
# Seed 004's Table 1, its pixel rows only (issue 28; the bandwidth rows
# need the seed's accounting in the rasteriser, not there yet): per preset
# of `shadowvol bench --scene` (simple, knights, demo) and size (1280x1024,
# 2048x1536), the pixels each method tests in the shadow (stencil) pass per
# frame, and the ratios to brute force and to depth bounds, beside the
# seed's figures. H is hier at the seed's 8x8 tiles and at the default 32.
# One bench run per preset and size (--quick: 2 frames, the minimum of 2
# runs; every stencil checked against bf's, byte for byte); its JSON is
# kept under OUT_DIR.
#
# usage: tools/table1_pixels.sh [BUILD_DIR] [OUT_DIR]
# (default: build, docs/results/table1; the table goes to OUT_DIR/pixels.md
# and standard output)
set -u
repo=$(cd "$(dirname "$0")/.." && pwd)
build="${1:-$repo/build}" out="${2:-$repo/docs/results/table1}"
sv="$build/shadowvol"
[ -x "$sv" ] || { echo "table1_pixels.sh: no $sv (build it first)" >&2; exit 2; }
mkdir -p "$out" || exit 2

# The value of KEY in the JSON row of METHOD on 1 thread (and TILE for hier).
field() { # FILE METHOD TILE KEY
  local pat="\"method\": \"$2\", \"threads\": 1,"
  [ "$3" != - ] && pat="\"method\": \"$2\", \"threads\": 1, \"tile\": $3,"
  grep -F "$pat" "$1" | head -1 | sed -E "s/.*\"$4\": ([0-9.e+-]+).*/\1/"
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0) printf "%.2f", a / b; else printf "-" }'; }

{
  echo "| preset | size | volume tris | BF px | DB px | H px (8) | H px (32) | BF / H (8) | DB / H (8) | BF / H (32) | BF / DB | all =bf |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
} >"$out/pixels.md.tmp"
status=0
for size in 1280x1024 2048x1536; do
  for preset in simple knights demo; do
    json="$out/${preset}_$size.json"
    if ! "$sv" bench --scene --preset "$preset" --size "$size" --quick --json "$json" \
        >"$out/${preset}_$size.txt" 2>&1; then
      echo "table1_pixels.sh: bench --scene --preset $preset --size $size failed" >&2
      status=1
      continue
    fi
    bf=$(field "$json" bf - pixels_tested_per_frame)
    db=$(field "$json" db - pixels_tested_per_frame)
    h8=$(field "$json" hier 8 pixels_tested_per_frame)
    h32=$(field "$json" hier 32 pixels_tested_per_frame)
    tris=$(field "$json" bf - volume_triangles_per_frame)
    equal=$(grep -c '"frames_equal_to_bf": 2}' "$json")
    rows=$(grep -c '"pass": "stencil"' "$json")
    echo "| $preset | $size | $tris | $bf | $db | $h8 | $h32 | $(ratio "$bf" "$h8") | $(ratio "$db" "$h8") | $(ratio "$bf" "$h32") | $(ratio "$bf" "$db") | $equal of $rows |" \
      >>"$out/pixels.md.tmp"
  done
done
{
  echo
  echo "The seed's Table 1 (1280x1024, its Mesa-based simulator, z-fail): pixels in the shadow pass"
  echo "(millions) BF / DB / H: Simple 0.28 / 0.25 / 0.02, Knights 25.67 / 9.78 / 3.48,"
  echo "Powerplant 2269 / 943 / 99, Amphitheater 5.03 / 4.74 / 0.94: 5.3-22.9x fewer than BF,"
  echo "2.8-11.5x fewer than DB."
} >>"$out/pixels.md.tmp"
mv "$out/pixels.md.tmp" "$out/pixels.md"
cat "$out/pixels.md"
exit $status
