#!/usr/bin/env bash
# Runs a test binary under qemu-x86_64 (Debian qemu-user) as a CPU this
# machine is not, and checks that dispatch saw that CPU: the binary's
# "[ dispatch ] ... level: L" line must name EXPECTED_LEVEL. QEMU's TCG
# emulates up to AVX2, never AVX-512, so Haswell gives the avx2 level and
# Nehalem (no AVX) the sse2 level on any host.
# SV_QEMU_TIERS (default: base) lists the passes, one run each: base is the
# baseline entry (every test naming no variant, the C and SSE2 variants),
# any other word an ISA tier (SV_TEST_ISA: tests/support/test_conditions.h), so a
# Haswell runs the baseline and then the avx2 tier. The exit status is the
# first pass's that is not 0 (77, a skip, when nothing failed).
# usage: run_under_qemu.sh QEMU CPU_MODEL EXPECTED_LEVEL BINARY [ARGS...]
set -u
qemu="$1"; cpu="$2"; want="$3"; shift 3
log=$(mktemp); trap 'rm -f "$log"' EXIT
status=0
for tier in ${SV_QEMU_TIERS:-base}; do
  isa=$tier; [ "$tier" = base ] && isa=
  echo "running under $qemu -cpu $cpu, tier $tier: $*"
  SV_TEST_ISA=$isa "$qemu" -cpu "$cpu" "$@" >"$log" 2>&1
  rc=$?
  cat "$log"
  if [ "$tier" = base ]; then
    level=$(sed -n 's/.*\[ dispatch \].* level: \([a-z0-9]*\);.*/\1/p' "$log" | head -1)
    if [ "$level" != "$want" ]; then
      echo "FAIL: under -cpu $cpu dispatch chose level '$level', expected '$want'"
      exit 1
    fi
    echo "qemu -cpu $cpu: dispatch level $level as expected"
  fi
  echo "qemu -cpu $cpu, tier $tier: test exit status $rc"
  if [ $rc -eq 1 ] || { [ $rc -ne 0 ] && [ $status -eq 0 ]; }; then status=$rc; fi
done
exit $status
