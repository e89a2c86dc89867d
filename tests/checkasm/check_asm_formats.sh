#!/bin/sh
# check_asm_formats.sh SRCDIR: assembles every asm source with nasm in each
# object format CMakeLists.txt claims for it, and checks the symbols each
# format needs. The lists are read from CMakeLists.txt, the one place that
# says what is built where:
#   SV_ASM_PORTED_FORMATS    the formats whose kernels are built; every
#                            source of asm/ assembles in each of them, except
#                            that on elf32 only SV_ASM_SSE2_SOURCES (the
#                            modules 32-bit targets build) do; the others
#                            must refuse elf32 with their %error rather than
#                            assemble wrongly (a module that assembles for
#                            elf32 but is not in that list fails too)
#   SV_ABI_CHECKER_FORMATS   src/check/abi_checked_call.asm and
#                            tests/checkasm/abi_selfcheck.asm assemble in each and
#                            export sv_abi_checked_call
# bench/machine/machine_limits.asm (`bench --limits`, built by the native x86-64
# program only) must assemble in every 64-bit format listed.
# Per format:
#   elf64, elf32  every sv_/svb_ function a FUNC symbol of nonzero size,
#                 and a .note.GNU-stack section (no executable stack);
#                 elf32 objects also have no absolute (R_386_32) relocation
#                 in .text (position-independent: no text relocation in a PIE)
#   macho64       the functions exported with the leading underscore
#                 (_sv_...), no unprefixed ones, no ELF-only sections
#   win64         the functions exported as sv_..., no .note.GNU-stack
# Needs nasm, llvm-nm (or nm) and readelf. Exit status: 0 all good, 1 a
# failure (each printed), 77 a tool missing (ctest: skipped).
set -u
src=${1:?usage: check_asm_formats.sh SRCDIR}
NM=$(command -v llvm-nm || command -v llvm-nm-14 || ls /usr/lib/llvm-*/bin/llvm-nm 2>/dev/null | head -n 1)
OBJDUMP=$(dirname "${NM:-/x}")/llvm-objdump; [ -x "$OBJDUMP" ] || OBJDUMP=objdump
for t in nasm readelf; do command -v $t >/dev/null || { echo "skip: no $t"; exit 77; }; done
[ -n "$NM" ] || { echo "skip: no llvm-nm"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
bad() { echo "FAIL: $*"; fail=1; }

# A list from CMakeLists.txt: the words of set(NAME ...), which may span
# lines.
cmake_list() {
    awk -v name="$1" '
        !on && $0 ~ "^set\\(" name "([ \t]|$)" { on = 1 }
        on { line = $0; sub(/#.*/, "", line); print line; if (line ~ /\)/) exit }
    ' "$src/CMakeLists.txt" | tr '()' '  ' | tr -s ' \t\n' '\n' |
        grep -v -x -e set -e "$1" -e ''
}
formats=$(cmake_list SV_ASM_PORTED_FORMATS | tr '\n' ' ')
checker_formats=$(cmake_list SV_ABI_CHECKER_FORMATS | tr '\n' ' ')
elf32_ok=$(cmake_list SV_ASM_SSE2_SOURCES | sed 's|.*/||; s|\.asm$||' | tr '\n' ' ')
[ -n "$formats" ] && [ -n "$elf32_ok" ] || { echo "FAIL: no format or module list in CMakeLists.txt"; exit 1; }
echo "formats: $formats; elf32 modules: $elf32_ok; checker: $checker_formats"

srcs="$src/asm/*.asm $src/bench/machine/machine_limits.asm"
n=0
for f in $srcs; do
    m=$(basename "$f" .asm)
    # the functions the source defines: FUNC name / FUNCTION name
    funcs=$(sed -n 's/^\s*FUNC\(TION\)\?\s\+\([A-Za-z_0-9]*\).*/\2/p' "$f")
    [ -n "$funcs" ] || bad "$m: no FUNC declarations found"
    for fmt in $formats; do
        o="$tmp/$m.$fmt.o"
        if ! nasm -f $fmt -I"$src/asm/" -o "$o" "$f" 2>"$tmp/err"; then
            case "$fmt:$m" in
            elf32:*) case " $elf32_ok " in *" $m "*) ;; *)
                grep -q "error" "$tmp/err" && continue;; esac;;
            esac
            bad "$m: nasm -f $fmt: $(head -n 3 "$tmp/err")"; continue
        fi
        if [ $fmt = elf32 ]; then
            case " $elf32_ok " in *" $m "*) ;; *) bad "$m: assembled for elf32 but is not in SV_ASM_SSE2_SOURCES";; esac
            readelf -rW "$o" | sed -n '/\.rel\.text/,/^$/p' | grep -q 'R_386_32 ' &&
                bad "$m.elf32: absolute R_386_32 relocation in .text (not position-independent)"
        fi
        n=$((n + 1))
        syms=$("$NM" --extern-only --defined-only "$o" | awk '{print $3}')
        for fn in $funcs; do
            case $fmt in
            macho64)
                echo "$syms" | grep -qx "_$fn" || bad "$m.$fmt: _$fn not exported"
                echo "$syms" | grep -qx "$fn" && bad "$m.$fmt: $fn exported without the underscore";;
            *)
                echo "$syms" | grep -qx "$fn" || bad "$m.$fmt: $fn not exported";;
            esac
            case $fmt in elf64|elf32)
                line=$(readelf -sW "$o" | awk -v s="$fn" '$8 == s')
                set -- $line
                [ "${4:-}" = FUNC ] || bad "$m.$fmt: $fn is not typed FUNC ($line)"
                [ "${3:-0}" != 0 ] || bad "$m.$fmt: $fn has size 0";;
            esac
        done
        case $fmt in
        elf64|elf32)
            readelf -SW "$o" | grep -q '\.note\.GNU-stack' || bad "$m.$fmt: no .note.GNU-stack";;
        *)
            "$OBJDUMP" -h "$o" 2>/dev/null | grep -q 'GNU-stack' && bad "$m.$fmt: has the ELF-only .note.GNU-stack";;
        esac
    done
done
# The ABI checker and its self-check routines.
for f in "$src/src/check/abi_checked_call.asm" "$src/tests/checkasm/abi_selfcheck.asm"; do
    m=$(basename "$f" .asm)
    for fmt in $checker_formats; do
        o="$tmp/$m.$fmt.o"
        if ! nasm -f $fmt -I"$src/src/check/" -o "$o" "$f" 2>"$tmp/err"; then
            bad "$m: nasm -f $fmt: $(head -n 3 "$tmp/err")"; continue
        fi
        n=$((n + 1))
        if [ $m = abi_checked_call ]; then
            want=sv_abi_checked_call; [ $fmt = macho64 ] && want=_sv_abi_checked_call
            "$NM" --extern-only --defined-only "$o" | awk '{print $3}' | grep -qx $want ||
                bad "$m.$fmt: $want not exported"
        fi
    done
done

echo "$n objects checked"
[ $n -gt 0 ] || fail=1
exit $fail
