#!/bin/sh
# The ABI checker's self-check on an ABI the main build does not produce:
#   elf32        elf32 cdecl (gcc -m32, Debian gcc-multilib), run natively
#   elf32_qemu   the same program under qemu-i386 -cpu coreduo (qemu-user)
#   win64        Windows x64 (mingw-w64), run under wine64
# Each broken routine of tests/checkasm/abi_selfcheck.asm must be reported with
# exactly its bit. One ABI per ctest entry: a missing tool exits 77 (the
# entry counts as skipped and ctest names it), a failing check exits 1.
# usage: check_abi_selfcheck_cross.sh elf32|elf32_qemu|win64 SOURCE_DIR WORK_DIR
set -eu
abi=$1; src=$2; work=$3
mkdir -p "$work"; cd "$work"
inc="-I$src/src/check/"
skip() { echo "SKIP: $*"; exit 77; }
case "$abi" in
  elf32|elf32_qemu)
    # The probe includes a libc header and links: `gcc -m32` alone runs
    # without the 32-bit headers and libraries (gcc-multilib), and an empty
    # probe passed there and the build below failed.
    printf '#include <stdio.h>\nint main(void) { return puts("") < 0; }\n' |
        gcc -m32 -x c - -o probe32 2>/dev/null || skip "no gcc -m32 with its libc (Debian gcc-multilib)"
    nasm $inc -f elf32 "$src/src/check/abi_checked_call.asm" -o acc32.o
    nasm $inc -f elf32 "$src/tests/checkasm/abi_selfcheck.asm" -o sc32.o
    gcc -m32 -O2 -I"$src/src/check" "$src/tests/checkasm/abi_selfcheck_main.c" \
        "$src/src/check/abi_check.c" acc32.o sc32.o -o selfcheck32
    if [ "$abi" = elf32 ]; then
      exec ./selfcheck32
    fi
    command -v qemu-i386 >/dev/null || skip "no qemu-i386 (Debian qemu-user)"
    exec qemu-i386 -cpu coreduo ./selfcheck32 ;;
  win64)
    command -v x86_64-w64-mingw32-gcc >/dev/null || skip "no x86_64-w64-mingw32-gcc (Debian gcc-mingw-w64-x86-64-posix)"
    wine=/usr/lib/wine/wine64
    [ -x "$wine" ] || skip "no $wine (Debian wine64)"
    nasm $inc -f win64 "$src/src/check/abi_checked_call.asm" -o accw.o
    nasm $inc -f win64 "$src/tests/checkasm/abi_selfcheck.asm" -o scw.o
    x86_64-w64-mingw32-gcc -O2 -I"$src/src/check" "$src/tests/checkasm/abi_selfcheck_main.c" \
        "$src/src/check/abi_check.c" accw.o scw.o -o selfcheck64.exe
    WINEDEBUG=-all WINEPREFIX="$work/wineprefix" exec "$wine" ./selfcheck64.exe ;;
  *) echo "usage: check_abi_selfcheck_cross.sh elf32|elf32_qemu|win64 SOURCE_DIR WORK_DIR" >&2; exit 2 ;;
esac
