#!/usr/bin/env bash
# Instructions per element of every kernel, counted by valgrind (callgrind),
# and with a result of `shadowvol bench --limits --json` from this CPU, the
# instructions per core cycle each kernel ran at: the measured bound of a
# kernel that no floor of `--limits` explains. A kernel near the core's
# issue width (4 to 6 per cycle on the cores this project has run on) is
# bound by what it executes; one far below it waits on something else
# (latency chains, mispredicted branches, the memory).
#
#   tools/instruction_counts.sh [--json RESULT.json] [SHADOWVOL]
#
# The counts come from `shadowvol bench --quick --regime moving` on the
# bundled character under callgrind: per kernel function (sv_<routine>_
# <variant>), its own instructions over its calls (warm-up and checked
# calls included: all on the same moving lights), over the elements of a
# call (triangles; SilEdges for create_sil_triangles, vertices for
# calculate_cull_bits). valgrind has no AVX-512, so the run is held to
# --isa avx2. With --json, the result's median ticks per element times its
# core_cycles_per_tick (the core clock over the TSC's, measured by --limits
# with a dependent add chain) give cycles per element, and their ratio is
# the kernel's instructions per cycle. Needs valgrind (apt-get install
# valgrind), and python3 for --json; takes about a minute.
set -euo pipefail
cd "$(dirname "$0")/.."
result=""
if [ "${1:-}" = --json ]; then result="$2"; shift 2; fi
sv="${1:-build/shadowvol}"
[ -x "$sv" ] || { echo "tools/instruction_counts.sh: $sv is not built" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "tools/instruction_counts.sh: needs valgrind (apt-get install valgrind)" >&2; exit 2; }
[ -z "$result" ] || [ -r "$result" ] || { echo "tools/instruction_counts.sh: cannot read $result" >&2; exit 2; }
[ -z "$result" ] || command -v python3 >/dev/null || { echo "tools/instruction_counts.sh: --json needs python3 (apt-get install python3)" >&2; exit 2; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" \
  "$sv" bench --quick --regime moving --isa avx2 >"$tmp/bench.txt" 2>"$tmp/valgrind.txt" \
  || { echo "tools/instruction_counts.sh: the bench under valgrind failed:" >&2; tail -5 "$tmp/valgrind.txt" >&2; exit 1; }
grep -q 'ok$' "$tmp/bench.txt" || { echo "tools/instruction_counts.sh: the bench checked nothing" >&2; exit 1; }
# The mesh's counts, from the bench's own header line.
read -r verts tris edges < <(sed -n 's/^mesh .*welded: \([0-9]*\) vertices, \([0-9]*\) triangles, \([0-9]*\) SilEdges.*/\1 \2 \3/p' "$tmp/bench.txt" | head -1)
[ -n "${edges:-}" ] || { echo "tools/instruction_counts.sh: no mesh line in the bench's output" >&2; exit 1; }

# Exclusive instructions per function, and calls per callee, from the
# callgrind file (names are compressed: "(id) name" once, "(id)" after).
awk -v verts="$verts" -v tris="$tris" -v edges="$edges" '
  function name_of(spec,   id, rest) {
    id = spec; sub(/\).*/, ")", id); rest = spec; sub(/^\([0-9]+\) ?/, "", rest)
    if (rest != "") names[id] = rest
    return id
  }
  /^fn=/  { cur = name_of(substr($0, 4)); incall = 0; next }
  /^cfn=/ { callee = name_of(substr($0, 5)); next }
  /^calls=/ { split(substr($0, 7), a, " "); calls[callee] += a[1]; incall = 1; next }
  /^[0-9+*-]/ { if (incall) { incall = 0; next }  # the cost of the call itself: inclusive, not ours
                n = split($0, f, " "); ir[cur] += f[n]; next }
  END {
    for (id in names) {
      fn = names[id]
      if (fn !~ /^sv_(calculate_facing_count|calculate_facing|calculate_cull_bits|count_facing_cull|count_facing|create_sil_triangles|create_cap_triangles)_/) continue
      if (!(id in calls) || calls[id] == 0) continue
      routine = fn; variant = fn
      sub(/^sv_/, "", routine)
      if (match(routine, /^(calculate_facing_count|calculate_facing|calculate_cull_bits|count_facing_cull|count_facing|create_sil_triangles|create_cap_triangles)_/)) {
        variant = substr(routine, RLENGTH + 1); routine = substr(routine, 1, RLENGTH - 1)
      }
      el = routine == "create_sil_triangles" ? edges : routine == "calculate_cull_bits" ? verts : tris
      printf "%s %s %d %.0f %.3f\n", routine, variant, calls[id], ir[id] / calls[id], ir[id] / calls[id] / el
    }
  }' "$tmp/cg.out" | sort >"$tmp/counts"

# ticks per element (median, moving light, first model) and the core clock, from RESULT
if [ -n "$result" ]; then
  python3 - "$result" >"$tmp/ticks" <<'PY' || { echo "tools/instruction_counts.sh: $result is not a bench --limits result" >&2; exit 2; }
import json, sys
d = json.load(open(sys.argv[1]))
cpt = d["limits"]["core_cycles_per_tick"]
model = d["results"][0]["model"]
print("clock", cpt)
for r in d["results"]:
    if r["model"] == model and r["regime"] == "moving" and r.get("checked"):
        print(r["routine"], r["variant"], r["ticks_per_element_median"])
PY
fi
printf 'instructions per element (valgrind callgrind, %s: %s triangles, %s SilEdges, %s vertices)\n' \
  "$(sed -n 's/^model  *\([^:]*\):.*/\1/p' "$tmp/bench.txt" | head -1)" "$tris" "$edges" "$verts"
if [ -n "$result" ]; then
  printf 'cycles per element: %s (median ticks per element) x its core_cycles_per_tick\n\n' "$result"
  printf '%-24s %-12s %8s %12s %10s %10s %6s\n' routine variant calls instr/call instr/elem cyc/elem IPC
else
  printf '\n%-24s %-12s %8s %12s %10s\n' routine variant calls instr/call instr/elem
fi
awk -v have="$([ -n "$result" ] && echo 1 || echo 0)" '
  FNR == NR && FILENAME ~ /ticks$/ { if ($1 == "clock") clock = $2; else t[$1 " " $2] = $3; next }
  { if (have && ($1 " " $2) in t && clock > 0) {
      cyc = t[$1 " " $2] * clock
      printf "%-24s %-12s %8d %12d %10.2f %10.2f %6.2f\n", $1, $2, $3, $4, $5, cyc, $5 / cyc
    } else if (have) {
      printf "%-24s %-12s %8d %12d %10.2f %10s %6s\n", $1, $2, $3, $4, $5, "-", "-"
    } else {
      printf "%-24s %-12s %8d %12d %10.2f\n", $1, $2, $3, $4, $5
    } }' $([ -n "$result" ] && echo "$tmp/ticks") "$tmp/counts"
