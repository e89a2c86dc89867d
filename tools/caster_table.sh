#!/usr/bin/env bash
# The speed/accuracy table of issue 27: per model and light kind, the
# paper's rule (--caster-rule closed) against auto (closed shells the
# paper's volume, the others two-sided): pixels wrong against the ray
# truth (off the shadow boundary / all), indices drawn, stencil pixels
# tested, and the volume job's TSC ticks per triangle (facing + culling +
# volume routines, the minimum of REPEATS runs on one thread, both rules
# in the same run). The caster's preparation (once per surface revision,
# kept in the VolumeCache) is not in these ticks. CAVEAT: each render is
# one cold frame in a fresh process, so the ticks include first-touch page
# faults of the volume buffers; under auto the caster's preparation has
# already grown the heap, so closed pays more of them (measured on spot.glb:
# 680k against 200k volume ticks for the same kernel work). Take the
# tk/tri column as an upper bound, not a like-for-like kernel ratio: that
# needs warm repeats inside one process (the next stop's benchmark).
#
# usage: tools/caster_table.sh [BUILD_DIR] [--mode zpass|zfail] [--size WxH] [--repeats N] [MODEL...]
# (default: the bundled character, every *.glb of ../shared/models and of
# ../shared/models/open, z-pass, 640x512, 5 repeats)
set -u
repo=$(cd "$(dirname "$0")/.." && pwd)
# shellcheck source=tools/table_args.sh
. "$repo/tools/table_args.sh"
build="$repo/build" mode=zpass size=640x512 repeats=5
table_args caster_table 16 "--mode --size --repeats" -- "$@"
[ -x "$sv" ] || { echo "caster_table: no $sv (build first)" >&2; exit 2; }
table_default_models
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT

# One line per (model, light, rule) from a render's JSON: the truth run and
# the minimum job ticks of the timing runs.
row() { # json_truth json_times...
  python3 - "$@" <<'EOF'
import json, sys
t = json.load(open(sys.argv[1]))
lf = t["lights"][0]
tri = sum(s["triangles"] for s in t["surfaces"])
ticks = min(sum(json.load(open(p))["lights"][0]["ticks"][k] for k in ("facing", "culling", "volume")
                if k in json.load(open(p))["lights"][0]["ticks"]) for p in sys.argv[2:])
tr = lf["truth"]
print(tr["off_boundary_mismatches"], tr["mismatches"], lf["drawn_indices"],
      lf["stencil_counters"]["pixels_tested"], "%.2f" % (ticks / tri), tri)
EOF
}

printf '%-22s %-5s | %-40s | %-40s\n' "" "" "--caster-rule closed (the paper's)" "auto (open shells the general rule)"
printf '%-22s %-5s | %9s %9s %10s %8s | %9s %9s %10s %8s\n' model light \
  "wrong" "indices" "st.pixels" "tk/tri" "wrong" "indices" "st.pixels" "tk/tri"
for m in "${models[@]}"; do
  name=$(basename "$m" .glb)
  for light in point spot dir; do
    line=$(printf '%-22s %-5s' "${name:0:22}" $light)
    for rule in closed auto; do
      out="$work/$name.$light.$rule"
      mkdir -p "$out"
      "$sv" render --add "$m" --ground --light $light:auto --size $size --mode $mode --no-gl \
        --caster-rule $rule --threads 1 --json "$out/truth.json" --out "$out" >/dev/null 2>&1
      times=()
      for r in $(seq 1 "$repeats"); do
        "$sv" render --add "$m" --ground --light $light:auto --size $size --mode $mode --no-gl \
          --no-truth --caster-rule $rule --threads 1 --json "$out/t$r.json" --out "$out" >/dev/null 2>&1
        times+=("$out/t$r.json")
      done
      read -r off all idx px tk tri < <(row "$out/truth.json" "${times[@]}")
      line+=$(printf ' | %9s %9s %10s %8s' "$off/$all" "$idx" "$px" "$tk")
    done
    echo "$line"
  done
done
echo "($mode, $size, one light per row placed by KIND:auto, the model on --ground; wrong: pixels"
echo " against the truth off the shadow boundary / in all; tk/tri: TSC ticks of"
echo " the facing, culling and volume routines per triangle of the scene, minimum of $repeats runs)"
