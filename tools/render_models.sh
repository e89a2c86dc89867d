#!/usr/bin/env bash
# The renderer on every model, alone on a ground plane, under a point, a
# spot and a directional light, in z-pass and in z-fail: the table of the
# issue that built the renderer (issue 12), from each run's own report.
#   tools/render_models.sh [BUILD_DIR] [WxH] [--stencil bf|db|hier] [--threads N]
#     (default build, 1280x1024, bf, every core)
# Our stencil pass and Mesa's are timed alike (render: the faster of two
# drawings each, Mesa with LP_NUM_THREADS = our thread count).
# Prints one row per model, mode and light; exits 1 if any run failed.
set -u
cd "$(dirname "$0")/.."
build=build size=1280x1024 method=bf threads="" positional=0
while [ $# -gt 0 ]; do
  case "$1" in
    --stencil) method="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    -*) echo "tools/render_models.sh: unknown option $1" >&2; exit 2 ;;
    *) if [ $positional -eq 0 ]; then build="$1"; else size="$1"; fi
       positional=$((positional + 1)); shift ;;
  esac
done
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
models=(models/character_1344.glb)
[ -d ../shared/models ] && models+=(../shared/models/*.glb)
printf '| model | mode | light | lit | shadowed | boundary | mismatches | off boundary | GL differing | GL other | stencil ms | Mesa stencil ms | Mesa / ours | depth ms | facing+volume ms |\n'
printf '|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n'
status=0
for m in "${models[@]}"; do
  for mode in zpass zfail; do
    name=$(basename "$m" .glb)
    "$build/shadowvol" render --add "$m" --ground --light point:auto --light spot:auto --light dir:auto \
      --size "$size" --mode "$mode" --stencil "$method" ${threads:+--threads "$threads"} \
      --out "$out/$name-$mode" >"$out/report" 2>"$out/err" || status=1
    depth=$(sed -n 's/^depth pass: .* written, \([0-9.]*\) ms.*/\1/p' "$out/report")
    for i in 0 1 2; do
      row=$(grep -E "^$i +(point|spot|directional)" "$out/report")
      gl=$(grep -E "^gl $i:" "$out/report")
      kind=$(echo "$row" | awk '{print $2}')
      # Columns after the light's text: vols zfail indices drawn | facing volume stencil shading | tested written bytes | lit shadowed boundary mism off | diff other ratio
      rest=$(echo "$row" | sed 's/^[^|]*|//')
      read -r facing volume stencil shading tested written bytes lit shadowed boundary mism off gdiff gother ratio <<<"$(echo "$rest" | tr '|' ' ')"
      mesa=$(echo "$gl" | sed -n "s/.*Mesa's stencil pass \([0-9.]*\) ms.*/\1/p")
      fv=$(awk -v a="$facing" -v b="$volume" 'BEGIN{printf "%.3f", a+b}')
      printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' \
        "$name" "$mode" "$kind" "$lit" "$shadowed" "$boundary" "$mism" "$off" "$gdiff" "$gother" \
        "$stencil" "${mesa:--}" "$ratio" "$depth" "$fv"
    done
  done
done
exit $status
