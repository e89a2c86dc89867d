# 32-bit x86 Linux (cdecl, ELF32) with the host GCC and Debian's multilib
# (gcc-multilib, g++-multilib). The programs run natively on an x86-64
# Linux and under qemu-i386 as 32-bit CPUs (docs/PLATFORMS.md):
#   cmake -S . -B build-i686 -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-i686.cmake
#   cmake --build build-i686 --target shadowvol_tests && ctest --test-dir build-i686
#
# SSE2 is required: CMakeLists.txt adds -msse2 -mfpmath=sse to every 32-bit
# build, so float arithmetic is rounded to float as on x86-64 (x87's excess
# precision would make the C reference, the oracle, differ from itself).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR i686)
set(CMAKE_C_COMPILER gcc)
set(CMAKE_CXX_COMPILER g++)
set(CMAKE_C_FLAGS_INIT "-m32")
set(CMAKE_CXX_FLAGS_INIT "-m32")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-m32")
set(CMAKE_SHARED_LINKER_FLAGS_INIT "-m32")
# NASM: elf32 by name (CMake's default for 32-bit Linux is `elf`, whose
# __OUTPUT_FORMAT__ asm/sv_abi.inc does not take for elf32).
set(CMAKE_ASM_NASM_OBJECT_FORMAT elf32)
# 32-bit libraries only (Debian's multiarch i386 folders), never the
# native 64-bit ones.
set(CMAKE_LIBRARY_ARCHITECTURE i386-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
