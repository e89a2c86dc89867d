#!/usr/bin/env bash
# The installable library (issue 16): installs BUILD_DIR into a fresh
# prefix, then builds and runs, with nothing from the source or build tree:
#   1. examples/consumer through find_package(shadowvol) (CMake): the C API
#      static and shared, the C++ mesh preparation static;
#   2. the C example through pkg-config, shared (`--libs`) and fully static
#      (`--static --libs` must bring the C++ runtime the C++ objects need).
# Also checks what the package holds (headers, both libraries, the config,
# the .pc) and that the shared library exports the routines.
# usage: check_install.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src="$1"; build="$2"
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"
fail() { echo "check_install: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix" >/dev/null || fail "cmake --install failed"
libdir=$(cd "$prefix" && ls -d lib*/ | head -1); libdir="${libdir%/}"
for f in include/shadowvol.h include/shadowvol_mesh.h include/shadowvol_planes.h include/shadowvol_skin.h "$libdir/libshadowvol.a" \
         "$libdir/cmake/shadowvol/shadowvolConfig.cmake" \
         "$libdir/cmake/shadowvol/shadowvolConfigVersion.cmake" \
         "$libdir/pkgconfig/shadowvol.pc"; do
  [ -f "$prefix/$f" ] || fail "the package lacks $f"
done
so=$(ls "$prefix/$libdir"/libshadowvol.so.* 2>/dev/null | head -1)
[ -n "$so" ] || fail "the package lacks libshadowvol.so.<version>"
[ -L "$prefix/$libdir/libshadowvol.so" ] || fail "libshadowvol.so (the link-time name) is missing"
# Every routine of the variant table is exported by the shared library.
exports=$(nm -D --defined-only "$so")
for sym in sv_best_variant sv_variants sv_count_facing_c_ref sv_create_shadow_volume_checked \
           sv_count_facing_sse2_paper sv_calculate_facing_c_ref sv_derive_planes_c_ref \
           sv_skin_planes_c_ref sv_skin_variants; do
  grep -qw "$sym" <<<"$exports" || fail "$so does not export $sym"
done

# 1. CMake consumer, configured against the prefix only.
cmake -S "$src/examples/consumer" -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" >"$work/configure.log" 2>&1 \
  || { cat "$work/configure.log" >&2; fail "find_package(shadowvol) consumer did not configure"; }
cmake --build "$work/consumer" >"$work/build.log" 2>&1 \
  || { cat "$work/build.log" >&2; fail "the consumer did not build against the installed package"; }
# The build must have used the installed headers, not the source tree's.
grep -rq -- "$src/include" "$work/consumer/build.ninja" && fail "the consumer saw the source tree's include/"
for exe in consumer_static_c consumer_shared_c consumer_mesh_cpp; do
  out=$("$work/consumer/$exe") || fail "$exe failed: $out"
  echo "$exe: $out"
done
# The shared consumer really runs against the installed .so.
linked=$(ldd "$work/consumer/consumer_shared_c")
grep -q "$prefix/$libdir/libshadowvol.so" <<<"$linked" \
  || fail "consumer_shared_c is not linked to the installed libshadowvol.so"

# 2. pkg-config: shared, then everything static (the .pc's Libs.private).
export PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig"
pc_version=$(pkg-config --modversion shadowvol) || fail "pkg-config does not find shadowvol.pc"
cc "$src/examples/consumer/tetrahedron_volume.c" $(pkg-config --cflags --libs shadowvol) \
   -Wl,-rpath,"$prefix/$libdir" -o "$work/pc_shared" || fail "pkg-config --libs link failed"
"$work/pc_shared" >/dev/null || fail "pkg-config shared program failed"
c++ "$src/examples/consumer/prepared_cube.cpp" -c -o "$work/cube.o" $(pkg-config --cflags shadowvol) \
  || fail "compile against pkg-config --cflags failed"
cc "$work/cube.o" -static $(pkg-config --static --libs shadowvol) -o "$work/pc_static" \
  || fail "pkg-config --static --libs does not bring what a static link of the C++ API needs"
"$work/pc_static" >/dev/null || fail "pkg-config static program failed"
echo "check_install: package $pc_version in $prefix: CMake consumer (3 programs) and pkg-config (shared, static) ok"
