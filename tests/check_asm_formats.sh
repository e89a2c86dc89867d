#!/bin/sh
# check_asm_formats.sh SRCDIR: assembles every asm source with nasm for each
# object format the ABI layer (asm/sv_abi.inc) supports and checks the
# symbols each format needs:
#   elf64    every sv_/svb_ function a FUNC symbol of nonzero size, and a
#            .note.GNU-stack section (no executable stack)
#   macho64  the functions exported with the leading underscore (_sv_...),
#            no unprefixed ones, no ELF-only sections
#   win64    the functions exported as sv_..., no .note.GNU-stack
#   elf32    the modules that support x86-32 (the SSE2 ports listed below)
#            assemble, with FUNC symbols; the x86-64-only ones refuse with
#            their %error rather than assembling wrongly.
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

# Modules known not to assemble for a format, with the reason (anything
# else must assemble).
no_win64=""                             # every module assembles for win64
elf32_ok="count_facing_sse2 count_facing_cull_sse2"

srcs="$src/asm/*.asm $src/bench/machine_limits.asm"
n=0
for f in $srcs; do
    m=$(basename "$f" .asm)
    # the functions the source defines: FUNC name / FUNCTION name
    funcs=$(sed -n 's/^\s*FUNC\(TION\)\?\s\+\([A-Za-z_0-9]*\).*/\2/p' "$f")
    [ -n "$funcs" ] || bad "$m: no FUNC declarations found"
    for fmt in elf64 macho64 win64 elf32; do
        o="$tmp/$m.$fmt.o"
        if ! nasm -f $fmt -I"$src/asm/" -o "$o" "$f" 2>"$tmp/err"; then
            case "$fmt:$m" in
            win64:*) case " $no_win64 " in *" $m "*) continue;; esac;;
            elf32:*) case " $elf32_ok " in *" $m "*) ;; *)
                grep -q "error" "$tmp/err" && continue;; esac;;
            esac
            bad "$m: nasm -f $fmt: $(head -n 3 "$tmp/err")"; continue
        fi
        if [ $fmt = elf32 ]; then
            case " $elf32_ok " in *" $m "*) ;; *) bad "$m: assembled for elf32 but is not in the list of 32-bit modules";; esac
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
echo "$n objects checked"
[ $n -gt 0 ] || fail=1
exit $fail
