#!/bin/sh
# The ABI checker's self-check on the ABIs the main build does not produce:
# elf32 cdecl (gcc -m32, run natively and under qemu-i386 -cpu coreduo) and
# Windows x64 (mingw-w64, run under wine64). Each broken routine of
# tests/abi_selfcheck.asm must be reported with exactly its bit. A missing
# tool skips that ABI with a message; a failing check fails the test.
# usage: check_abi_selfcheck_cross.sh SOURCE_DIR WORK_DIR
set -eu
src=$1; work=$2
mkdir -p "$work"; cd "$work"
inc="-I$src/src/check/"
status=0
if gcc -m32 -x c /dev/null -c -o /dev/null 2>/dev/null; then
    nasm $inc -f elf32 "$src/src/check/abi_checked_call.asm" -o acc32.o
    nasm $inc -f elf32 "$src/tests/abi_selfcheck.asm" -o sc32.o
    gcc -m32 -O2 -I"$src/src/check" "$src/tests/abi_selfcheck_main.c" \
        "$src/src/check/abi_check.c" acc32.o sc32.o -o selfcheck32
    ./selfcheck32 || status=1
    if command -v qemu-i386 >/dev/null; then
        qemu-i386 -cpu coreduo ./selfcheck32 || status=1
    else
        echo "qemu-i386 missing: elf32 under an SSE3 Core Duo not checked"
    fi
else
    echo "gcc -m32 unavailable (gcc-multilib): elf32 not checked"
fi
wine=/usr/lib/wine/wine64
if command -v x86_64-w64-mingw32-gcc >/dev/null && [ -x "$wine" ]; then
    nasm $inc -f win64 "$src/src/check/abi_checked_call.asm" -o accw.o
    nasm $inc -f win64 "$src/tests/abi_selfcheck.asm" -o scw.o
    x86_64-w64-mingw32-gcc -O2 -I"$src/src/check" "$src/tests/abi_selfcheck_main.c" \
        "$src/src/check/abi_check.c" accw.o scw.o -o selfcheck64.exe
    WINEDEBUG=-all "$wine" ./selfcheck64.exe || status=1
else
    echo "mingw-w64 or wine64 missing: win64 not checked"
fi
exit $status
