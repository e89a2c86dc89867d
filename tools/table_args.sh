# shellcheck shell=bash
# shellcheck disable=SC2034  # every variable set here is the sourcing script's
# The arguments the table tools share (caster_table.sh, extrude_table.sh,
# extrude_skinned_table.sh), sourced by each: BUILD_DIR, MODEL.glb ... and
# the options each names. The script sets its defaults (build, size,
# repeats, mode, fps, png) before and reads them after.
#
#   table_args NAME HELP_LAST OPTIONS -- ARGS...
#     OPTIONS: the space-separated options NAME takes, of --mode, --size,
#     --repeats, --fps, --png (each with a value); -h/--help prints NAME's
#     header lines 2..HELP_LAST; another option: exit 2. Sets build,
#     models (the .glb arguments), sv (BUILD_DIR/shadowvol).
#   table_default_models
#     models, when none was given: the bundled character, then every model
#     of ../shared/models and its open/ folder.

table_args() {
  local name=$1 help_last=$2 options=" $3 "
  shift 4
  models=()
  while [ $# -gt 0 ]; do
    case "$1" in
      -h|--help) sed -n "2,${help_last}p" "$0"; exit 0 ;;
      --*)
        case "$options" in *" $1 "*) ;; *) echo "$name: unknown option $1" >&2; exit 2 ;; esac
        [ $# -ge 2 ] || { echo "$name: $1 needs a value" >&2; exit 2; }
        case "$1" in
          --mode) mode="$2" ;;
          --size) size="$2" ;;
          --repeats) repeats="$2" ;;
          --fps) fps="$2" ;;
          --png) png="$2" ;;
        esac
        shift 2 ;;
      *.glb) models+=("$1"); shift ;;
      *) build="$1"; shift ;;
    esac
  done
  sv="$build/shadowvol"
}

table_default_models() {
  [ ${#models[@]} -eq 0 ] || return 0
  models=("$repo/models/character_1344.glb")
  local m
  for m in "$repo"/../shared/models/*.glb "$repo"/../shared/models/open/*.glb; do
    [ -f "$m" ] && models+=("$m")
  done
}
