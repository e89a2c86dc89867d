#!/usr/bin/env bash
# The core-only `shadowvol bench` (bench/suites/bench_core_main.cpp; 32-bit x86):
# --quick prints the cycle table with a row per routine for c_ref and
# exits 0 (every row checked against the reference); --limits, whose probes
# are System V x86-64 asm, and unknown options are refused with status 2
# and a message.
# usage: check_bench_core.sh SHADOWVOL
set -u
exe="$1"
fail=0
out=$("$exe" bench --quick 2>&1); rc=$?
echo "$out"
[ $rc -eq 0 ] || { echo "FAIL: bench --quick exited $rc"; fail=1; }
for routine in count_facing count_facing_cull create_sil_triangles create_cap_triangles; do
  echo "$out" | grep -q "$routine" || { echo "FAIL: no row for $routine"; fail=1; }
done
echo "$out" | grep -q "c_ref" || { echo "FAIL: no c_ref column or row"; fail=1; }
err=$("$exe" bench --limits 2>&1); rc=$?
[ $rc -eq 2 ] || { echo "FAIL: --limits exited $rc, expected 2"; fail=1; }
echo "$err" | grep -q "not in this build" || { echo "FAIL: --limits message: $err"; fail=1; }
"$exe" bench --no-such-option >/dev/null 2>&1; rc=$?
[ $rc -eq 2 ] || { echo "FAIL: an unknown option exited $rc, expected 2"; fail=1; }
[ $fail -eq 0 ] && echo "check_bench_core: ok"
exit $fail
