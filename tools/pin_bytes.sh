#!/usr/bin/env bash
# Pins the bytes shadowvol writes today (issue 25), so that a change meant
# to move files around, add a pass or replace a kernel can prove it changed
# no picture and no index list, and one meant to change them says which.
#
#   tools/pin_bytes.sh --write [BUILD_DIR] [--set bundled|shared|all]
#   tools/pin_bytes.sh --check [BUILD_DIR] [--set bundled|shared|all]
#
# What it runs (BUILD_DIR default: build):
#   - for every model, the bundled models/character_1344.glb, every
#     *.glb at the top of the shared models folder (../shared/models, or
#     --models DIR) and every *.glb of its open/ folder (keys
#     shared/open/...), in z-pass and in z-fail:
#       shadowvol render --add MODEL --ground --light point:auto
#         --light spot:auto --light dir:auto --size 320x256 --mode M --no-gl
#     and records the sha256 of every PNG it writes (shaded, stencil,
#     truth), each volume's index count and FNV-1a 64 from the JSON
#     report (index_lists), and its exit status. Mesa is left out: its
#     pixels depend on Mesa's version, not on this project;
#   - the demo scene the build writes (BUILD_DIR/models/demo_scene.glb):
#     shadowvol scene, 4 frames at 320x256, the sha256 of every PNG
#     (frames, contact sheet, any truth picture) and its exit status.
# A run that exits non-zero is recorded, not dropped: a real model failing
# its truth is a finding the manifest keeps visible.
#
# The manifest (tests/cli/pinned_bytes.manifest, or --manifest FILE) holds one
# sorted line per item, "KEY VALUE"; the shared models' keys begin with
# "shared/" so the bundled set is checked alone where that folder is
# missing. --write replaces the lines of the chosen set and keeps the
# others. --check prints "changed KEY OLD NEW", "missing KEY" (in the
# manifest, not written now) and "new KEY" (written now, not in the
# manifest) for each difference, then a count, and exits 1 on any
# difference; 77 when the shared set is asked for and its folder is
# missing (ctest reports a skip); 2 on bad arguments.
#
# The run's files go to --work DIR (default: a temporary folder, removed
# when the check passes and kept, with its path printed, when it fails, so
# the changed pictures can be looked at).
#
# Only bash, coreutils (sha256sum, sort, join) and sed, besides shadowvol.
set -u
export LC_ALL=C

repo=$(cd "$(dirname "$0")/.." && pwd)
action="" build="" set_name="all" models="$repo/../shared/models" manifest="$repo/tests/cli/pinned_bytes.manifest" work=""
usage() {
  if [ "${1:-2}" = 0 ]; then
    sed -n '2,/^set -u/{/^set -u/d;s/^# \{0,1\}//;p}' "$0"
  else
    echo "usage: tools/pin_bytes.sh --write|--check [BUILD_DIR] [--set bundled|shared|all] [--models DIR] [--manifest FILE] [--work DIR] (--help)" >&2
  fi
  exit "${1:-2}"
}
while [ $# -gt 0 ]; do
  case "$1" in
    --write|--check) action=${1#--} ;;
    --set) [ $# -ge 2 ] || usage; set_name=$2; shift ;;
    --models) [ $# -ge 2 ] || usage; models=$2; shift ;;
    --manifest) [ $# -ge 2 ] || usage; manifest=$2; shift ;;
    --work) [ $# -ge 2 ] || usage; work=$2; shift ;;
    -h|--help) usage 0 ;;
    -*) echo "pin_bytes: unknown option $1" >&2; usage ;;
    *) [ -z "$build" ] || { echo "pin_bytes: one build folder, not $build and $1" >&2; exit 2; }
       build=$1 ;;
  esac
  shift
done
[ -n "$action" ] || { echo "pin_bytes: say --write or --check" >&2; usage; }
case "$set_name" in bundled|shared|all) ;; *) echo "pin_bytes: --set bundled, shared or all, not $set_name" >&2; exit 2 ;; esac
build=${build:-$repo/build}
sv="$build/shadowvol"
demo="$build/models/demo_scene.glb"
[ -x "$sv" ] || { echo "pin_bytes: no $sv (build shadowvol_cli first)" >&2; exit 2; }

want_bundled=0 want_shared=0
[ "$set_name" = shared ] || want_bundled=1
[ "$set_name" = bundled ] || want_shared=1
if [ $want_shared = 1 ] && ! [ -d "$models" ]; then
  if [ "$action" = write ]; then
    # Writing "all" without the shared models would drop their lines.
    echo "pin_bytes: no shared models folder $models: the shared set cannot be written here (--set bundled writes the rest)" >&2
    exit 2
  fi
  if [ "$set_name" = shared ]; then
    echo "pin_bytes: no shared models folder $models: the shared set is not checked here (skipped)"
    exit 77
  fi
  echo "NOTE: no shared models folder $models: checking the bundled set only"
  want_shared=0
fi
if [ $want_bundled = 1 ] && ! [ -f "$demo" ]; then
  echo "pin_bytes: no $demo (build shadowvol_demo_scene first)" >&2; exit 2
fi

keep_work=1
if [ -z "$work" ]; then
  work=$(mktemp -d) || exit 2
  keep_work=0
  trap '[ $keep_work = 1 ] || rm -rf "$work"' EXIT
else
  # Only what an earlier run wrote there is removed, never the folder itself.
  mkdir -p "$work" && rm -rf "$work/render" "$work/scene" "$work/shared" "$work/now.txt" "$work/expected.txt" \
      "$work/kept.txt" || { echo "pin_bytes: cannot use --work $work" >&2; exit 2; }
fi

# Threads are fixed so every machine runs the same job; the pictures are the
# same at any count (docs/RENDERING.md), and 2 keeps ctest -j from
# oversubscribing a large machine.
threads=2
size=320x256

# png_lines KEY_PREFIX DIR: one line per PNG in DIR.
png_lines() {
  local f
  for f in "$2"/*.png; do
    [ -e "$f" ] || continue
    echo "$1/$(basename "$f") $(sha256sum <"$f" | cut -d' ' -f1)"
  done
}

# render_lines KEY_PREFIX MODEL: both modes of one model.
render_lines() {
  local prefix=$1 model=$2 name mode out rc
  name=$(basename "$model" .glb | tr -c 'A-Za-z0-9_.\n-' '_')
  for mode in zpass zfail; do
    out="$work/$prefix/$name/$mode"
    mkdir -p "$out"
    "$sv" render --add "$model" --ground --light point:auto --light spot:auto --light dir:auto \
        --size $size --mode $mode --no-gl --threads $threads --json "$out/render.json" --out "$out" \
        >"$out/stdout" 2>"$out/stderr"
    rc=$?
    echo "$prefix/$name/$mode/exit $rc"
    [ $rc -eq 0 ] || echo "NOTE: render of $name in $mode exited $rc (recorded)" >&2
    png_lines "$prefix/$name/$mode" "$out"
    # One JSON row per volume: {"light": L, "surface": S, ..., "indices": N, ..., "indices_fnv1a64": "H"}
    [ -f "$out/render.json" ] && sed -n \
      's|.*{"light": \([0-9]*\), "surface": \([0-9]*\), .*"indices": \([0-9]*\), .*"indices_fnv1a64": "\([0-9a-f]*\)".*|'"$prefix/$name/$mode"'/light\1/surface\2/indices \3:\4|p' \
      "$out/render.json"
  done
}

scene_lines() {
  local out="$work/scene/demo_scene" rc
  mkdir -p "$out"
  "$sv" scene "$demo" --size $size --frames 4 --threads $threads --out "$out" --json "$out/scene.json" \
      >"$out/stdout" 2>"$out/stderr"
  rc=$?
  echo "scene/demo_scene/exit $rc"
  [ $rc -eq 0 ] || echo "NOTE: scene of the demo exited $rc (recorded)" >&2
  png_lines scene/demo_scene "$out"
}

now="$work/now.txt"
{
  if [ $want_bundled = 1 ]; then
    render_lines render "$repo/models/character_1344.glb"
    scene_lines
  fi
  if [ $want_shared = 1 ]; then
    for m in "$models"/*.glb; do
      [ -f "$m" ] && render_lines shared/render "$m"
    done
    # The open and non-manifold characters (issue 27), under their own prefix.
    for m in "$models"/open/*.glb; do
      [ -f "$m" ] && render_lines shared/open/render "$m"
    done
  fi
} | sort >"$now"

# in_set: the manifest's lines of the chosen set(s), comments dropped.
in_set() {
  grep -v '^#' "$1" | grep -v '^$' | {
    if [ $want_bundled = 1 ] && [ $want_shared = 1 ]; then cat
    elif [ $want_shared = 1 ]; then grep '^shared/'
    else grep -v '^shared/'
    fi
  } | sort
}

if [ "$action" = write ]; then
  kept="$work/kept.txt"
  : >"$kept"
  if [ -f "$manifest" ]; then
    # The other set's lines stay as they are.
    grep -v '^#' "$manifest" | grep -v '^$' | {
      if [ $want_bundled = 1 ] && [ $want_shared = 1 ]; then :
      elif [ $want_shared = 1 ]; then grep -v '^shared/'
      else grep '^shared/'
      fi
    } >"$kept"
  fi
  {
    cat <<'EOF'
# The bytes shadowvol writes today (issue 25): one "KEY VALUE" line per item.
# render/MODEL/MODE/...: shadowvol render --add MODEL --ground --light point:auto
#   --light spot:auto --light dir:auto --size 320x256 --mode MODE --no-gl:
#   FILE.png the sha256 of the picture; lightL/surfaceS/indices the number of
#   indices of that volume and their FNV-1a 64 (the JSON's index_lists);
#   exit the command's exit status.
# scene/demo_scene/...: shadowvol scene (the build's demo scene), 4 frames at 320x256.
# shared/...: the same for every *.glb at the top of ../shared/models, and
# shared/open/... for every *.glb of ../shared/models/open (issue 27).
# Check: tools/pin_bytes.sh --check [BUILD_DIR] (ctest -R pinned_bytes).
# Regenerate: tools/pin_bytes.sh --write [BUILD_DIR], in the same commit as
# the intended change, with the reason in the commit message.
EOF
    sort "$kept" "$now"
  } >"$manifest.tmp" && mv "$manifest.tmp" "$manifest" || { echo "pin_bytes: cannot write $manifest" >&2; exit 2; }
  echo "pin_bytes: wrote $(wc -l <"$now") line(s) of the $set_name set to $manifest"
  exit 0
fi

[ -f "$manifest" ] || { echo "pin_bytes: no manifest $manifest (make it with --write)" >&2; exit 2; }
expected="$work/expected.txt"
in_set "$manifest" >"$expected"
# KEY OLD NEW, with "-" where a side has no such key.
differences=0
while read -r key old new; do
  if [ "$old" = "$new" ]; then continue; fi
  differences=$((differences + 1))
  if [ "$old" = - ]; then echo "new $key"
  elif [ "$new" = - ]; then echo "missing $key"
  else echo "changed $key $old $new"
  fi
done < <(join -a 1 -a 2 -e - -o 0,1.2,2.2 "$expected" "$now")
echo "pin_bytes: $(wc -l <"$now") line(s) of the $set_name set against $manifest: $differences difference(s)"
if [ $differences -gt 0 ]; then
  keep_work=1
  echo "pin_bytes: this run's pictures and reports are in $work"
  echo "pin_bytes: an intended change regenerates the manifest (tools/pin_bytes.sh --write) in the same commit, with the reason in the commit message"
  exit 1
fi
exit 0
