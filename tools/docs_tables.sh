#!/usr/bin/env bash
# Writes the docs' generated tables from the committed results in
# docs/results/ (issue 17: a figure never goes stale without this script
# saying so). Every block of README.md and docs/*.md between
#   <!-- BEGIN GENERATED: shadowvol bench --report docs/results/X.json -->
#   <!-- END GENERATED -->
# (or `shadowvol bench --compare A.json B.json`, written in a code block) is
# replaced by what that command prints now.
#
#   tools/docs_tables.sh [--check] [SHADOWVOL]
#
# --check changes nothing: it reports every block whose text differs from
# what the command prints, and exits 1 if there is one (the ctest
# docs_tables_current runs it). SHADOWVOL defaults to build/shadowvol.
set -euo pipefail
cd "$(dirname "$0")/.."
check=0
if [ "${1:-}" = --check ]; then check=1; shift; fi
sv="${1:-build/shadowvol}"
[ -x "$sv" ] || { echo "tools/docs_tables.sh: $sv is not built" >&2; exit 2; }
stale=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for doc in README.md docs/*.md; do
  grep -q '<!-- BEGIN GENERATED: ' "$doc" || continue
  out="$tmp/out.md"; : >"$out"
  in_block=0
  while IFS= read -r line || [ -n "$line" ]; do
    if [ $in_block -eq 1 ]; then
      case "$line" in '<!-- END GENERATED -->') in_block=0; printf '%s\n' "$line" >>"$out" ;; esac
      continue
    fi
    printf '%s\n' "$line" >>"$out"
    case "$line" in
      '<!-- BEGIN GENERATED: shadowvol bench --report '*' -->'|'<!-- BEGIN GENERATED: shadowvol bench --compare '*' -->')
        cmd=${line#'<!-- BEGIN GENERATED: shadowvol '}; cmd=${cmd%' -->'}
        read -r -a args <<<"$cmd"
        for a in "${args[@]}"; do
          case "$a" in bench|--report|--compare|--regime|moving|fixed|--routine|docs/results/*.json) ;;
            pipeline|pipeline_cull|calculate_facing|calculate_cull_bits|count_facing|count_facing_cull|create_sil_triangles|create_cap_triangles|create_shadow_volume|create_shadow_volume_cull) ;;
            *) echo "$doc: refusing to run '$cmd' (only bench --report / --compare of docs/results/)" >&2; exit 2 ;;
          esac
        done
        if ! "$sv" "${args[@]}" >"$tmp/block" 2>"$tmp/err"; then
          echo "$doc: shadowvol $cmd failed: $(cat "$tmp/err")" >&2; exit 1
        fi
        case "$cmd" in *--compare*) { echo '```text'; cat "$tmp/block"; echo '```'; } >>"$out" ;;
                       *) cat "$tmp/block" >>"$out" ;; esac
        in_block=1 ;;
    esac
  done <"$doc"
  if [ $in_block -eq 1 ]; then echo "$doc: a GENERATED block has no END" >&2; exit 1; fi
  if ! cmp -s "$doc" "$out"; then
    if [ $check -eq 1 ]; then
      echo "STALE: $doc: a generated table differs from what docs/results/ gives now:" >&2
      diff -u "$doc" "$out" | head -20 >&2 || true
      stale=1
    else
      cp "$out" "$doc"; echo "tools/docs_tables.sh: wrote $doc"
    fi
  fi
done
[ $check -eq 0 ] || [ $stale -eq 0 ] && { [ $check -eq 0 ] || echo "docs_tables: every generated table is current"; }
exit $stale
