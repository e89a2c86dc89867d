#!/bin/sh
# run.sh SRCDIR [QEMU]: builds the four faithful SSE2 ports (App. C-F)
# as elf32 objects with nasm, links them with the C reference and
# sse2_kernels_main.c by gcc -m32 (multilib), and runs the result natively
# or under QEMU (e.g. "qemu-i386 -cpu coreduo"). Exit 77 without multilib.
set -eu
src=${1:?usage: run.sh SRCDIR [QEMU...]}; shift
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
echo 'int main(void){return 0;}' > "$tmp/t.c"
gcc -m32 -o "$tmp/t" "$tmp/t.c" 2>/dev/null || { echo "skip: no gcc -m32"; exit 77; }
for m in count_facing_sse2 count_facing_cull_sse2 create_sil_triangles_sse2 create_cap_triangles_sse2; do
    nasm -f elf32 -I"$src/asm/" -o "$tmp/$m.o" "$src/asm/$m.asm"
done
gcc -m32 -msse2 -O1 -I"$src/include" -o "$tmp/x86_32_sse2" \
    "$src/tests/checkasm/x86_32/sse2_kernels_main.c" "$src/src/core/ref/reference_paper.c" "$tmp"/*.o
"$@" "$tmp/x86_32_sse2"
