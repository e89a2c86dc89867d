#!/usr/bin/env bash
# Runs a test binary under qemu-x86_64 (Debian qemu-user) as a CPU this
# machine is not, and checks that dispatch saw that CPU: the binary's
# "[ dispatch ] ... level: L" line must name EXPECTED_LEVEL. QEMU's TCG
# emulates up to AVX2, never AVX-512, so Haswell gives the avx2 level and
# Nehalem (no AVX) the sse2 level on any host.
# usage: run_under_qemu.sh QEMU CPU_MODEL EXPECTED_LEVEL BINARY [ARGS...]
set -u
qemu="$1"; cpu="$2"; want="$3"; shift 3
log=$(mktemp); trap 'rm -f "$log"' EXIT
echo "running under $qemu -cpu $cpu: $*"
"$qemu" -cpu "$cpu" "$@" >"$log" 2>&1
rc=$?
cat "$log"
level=$(sed -n 's/.*\[ dispatch \].* level: \([a-z0-9]*\);.*/\1/p' "$log" | head -1)
if [ "$level" != "$want" ]; then
  echo "FAIL: under -cpu $cpu dispatch chose level '$level', expected '$want'"
  exit 1
fi
echo "qemu -cpu $cpu: dispatch level $level as expected; test exit status $rc"
exit $rc
