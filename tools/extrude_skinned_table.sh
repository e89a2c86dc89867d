#!/usr/bin/env bash
# Seed 002's skinned artifact over whole animations (issue 31; the seed's
# Figure 4 and its fixes): for each skinned, animated character (the demo
# scene's, then those of ../shared/models and open/), its first animation
# at FPS frames a second, three lights around each posed surface (a point
# light with a range, the same without, a sun), the faces the seed's
# program splits (its three vertices disagree on facing) with the face
# normal skinned per vertex (straightforward), by face weights, recomputed
# from the skinned positions, and from the neighbours with one shared
# facing expression. One line per character: the totals over frames and
# lights, and the worst frame. Then, per character, its open edges and the
# shadow pixels that differ from the frame with the recomputed normals
# (160x120, a point light, the seed's volumes under --caster-rule closed)
# with the normals skinned per vertex, by face weights and from the
# neighbours. (The ctest entries extrude_skinned and
# extrude_skinned_shared_models run 4 and 2 frames.)
#
# --png FILE: the README's artifact image: the worst straightforward frame of
# the characters without open edges at 480x360, cropped to the notch and
# enlarged twice, the normals skinned per vertex, by face weights and from
# the neighbours side by side (pixels whose shadow differs from the
# recomputed normals' magenta).
#
# usage: tools/extrude_skinned_table.sh [BUILD_DIR] [--fps F] [--png FILE]   (default 30, no image)
set -u
repo=$(cd "$(dirname "$0")/.." && pwd)
# shellcheck source=tools/table_args.sh
. "$repo/tools/table_args.sh"
build="$repo/build" fps=30 png=
table_args extrude_skinned_table 24 "--fps --png" -- "$@"
t="$build/tests/shadowvol_extrude_skinned_tests"
[ -x "$t" ] || { echo "extrude_skinned_table: no $t (build first)" >&2; exit 2; }
SV_TEST_SHARED_MODELS=1 SV_EXTRUDE_SKINNED_FPS="$fps" SV_EXTRUDE_SKINNED_PNG="$png" "$t" --gtest_filter='*SharedModels*' \
  | sed -n 's/^\[ skinned  \] //p; s/^\[ pixels   \] /pixels: /p; s/^\[ image    \] /image: /p'
echo "command: tools/extrude_skinned_table.sh --fps $fps${png:+ --png $png}"
