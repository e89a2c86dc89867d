#!/usr/bin/env bash
# Seed 004's Table 1 (issue 28): per preset of `shadowvol bench --scene`
# (simple, knights, demo) and size (1280x1024, 2048x1536), the pixels each
# method tests in the shadow (stencil) pass per frame, and the ratios to
# brute force and to depth bounds, beside the seed's figures
# (OUT_DIR/pixels.md); and the bandwidth rows with the seed's accounting,
# the bench's counted model (OUT_DIR/bandwidth.md; scene_pass_table.cpp's
# bandwidth_model says what is counted). H is hier at the seed's 8x8
# tiles (and at the default 32 for the pixels).
# One bench run per preset and size (--quick: 2 frames, the minimum of 2
# runs; every stencil checked against bf's, byte for byte); its JSON is
# kept under OUT_DIR.
#
# usage: tools/table1_pixels.sh [BUILD_DIR] [OUT_DIR]
# (default: build, docs/results/table1; the tables go to OUT_DIR/pixels.md,
# OUT_DIR/bandwidth.md and standard output)
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
mb() { awk -v a="$1" 'BEGIN { printf "%.3f", a / 1e6 }'; }
{
  echo "| preset | size | method | stencil BW, shadow pass | Z BW, shadow pass | stencil BW, lighting | PSV BW | delay stream BW | total | pixels (M) | BF / this, BW | BF / this, pixels |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
} >"$out/bandwidth.md.tmp"
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
    rows=$(grep -c '"pass": "stencil", "method"' "$json")
    echo "| $preset | $size | $tris | $bf | $db | $h8 | $h32 | $(ratio "$bf" "$h8") | $(ratio "$db" "$h8") | $(ratio "$bf" "$h32") | $(ratio "$bf" "$db") | $equal of $rows |" \
      >>"$out/pixels.md.tmp"
    bf_total=$(field "$json" bf - bw_total)
    for m in bf db hier; do
      t=-
      [ "$m" = hier ] && t=8
      total=$(field "$json" "$m" "$t" bw_total)
      px=$(field "$json" "$m" "$t" pixels_tested_per_frame)
      echo "| $preset | $size | $m${t/-/} | $(mb "$(field "$json" "$m" "$t" bw_stencil_shadow)") | $(mb "$(field "$json" "$m" "$t" bw_z_shadow)") | $(mb "$(field "$json" "$m" "$t" bw_stencil_lighting)") | $(mb "$(field "$json" "$m" "$t" bw_psv)") | $(mb "$(field "$json" "$m" "$t" bw_delay)") | $(mb "$total") | $(mb "$px") | $(ratio "$bf_total" "$total") | $(ratio "$bf" "$px") |" \
        >>"$out/bandwidth.md.tmp"
    done
  done
done
{
  echo
  echo "The seed's Table 1 (1280x1024, its Mesa-based simulator, z-fail): pixels in the shadow pass"
  echo "(millions) BF / DB / H: Simple 0.28 / 0.25 / 0.02, Knights 25.67 / 9.78 / 3.48,"
  echo "Powerplant 2269 / 943 / 99, Amphitheater 5.03 / 4.74 / 0.94: 5.3-22.9x fewer than BF,"
  echo "2.8-11.5x fewer than DB."
} >>"$out/pixels.md.tmp"
{
  echo
  echo "MB per frame, all lights. The seed's Table 1 (1280x1024, one light, z-fail), total bandwidth"
  echo "BF / DB / H in MB: Simple 1.82 / 1.77 / 0.10, Knights 52.78 / 22.46 / 9.40, Powerplant"
  echo "4490 / 1959 / 283, Amphitheater 11.37 / 10.82 / 2.91: 3.9-17.6x less than BF. Its Knights"
  echo "H row: stencil 5.90, Z 2.93, lighting 0.11, PSV 0.035, delay stream 0.43."
} >>"$out/bandwidth.md.tmp"
mv "$out/pixels.md.tmp" "$out/pixels.md"
mv "$out/bandwidth.md.tmp" "$out/bandwidth.md"
cat "$out/pixels.md" "$out/bandwidth.md"
exit $status
