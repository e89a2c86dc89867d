# The installable library (issue 16): `cmake --install <build> --prefix P`
# puts in place
#   P/include/shadowvol.h, shadowvol_planes.h,  the C API (routines; per-frame planes;
#     shadowvol_skin.h                          skinning, with planes in one pass;
#     shadowvol_plan.h                          dispatch by measurement)
#   P/include/shadowvol_mesh.h                  the C++ mesh preparation
#   P/include/shadowvol_casters.h               shells and the caster rule (issue 27)
#   P/lib/libshadowvol.a                        static (imported shadowvol::shadowvol)
#   P/lib/libshadowvol.so.<version>             shared (imported shadowvol::shadowvol_shared)
#   P/lib/cmake/shadowvol/                      find_package(shadowvol) config
#   P/lib/pkgconfig/shadowvol.pc                pkg-config (--static adds the C++ runtime)
# Only the core library is installed: the glTF loader, the verifier, the
# renderer and the scene are the program's and the tests' (they pull in
# tinygltf, TBB and OSMesa), not part of the library's API.
#
# The shared library is compiled from the static one's sources (their list
# and flags are read from the target, so a platform that leaves an asm file
# out leaves it out of both), as position-independent code; the asm is PIC
# already (RIP-relative data, calls between kernels through the PLT).

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

get_target_property(_sv_core_sources shadowvol SOURCES)
get_target_property(_sv_core_options shadowvol COMPILE_OPTIONS)
# The per-platform asm definitions (SV_HAVE_ASM_*: which variants
# src/core/variants.c lists), or the shared library's table would lack the asm.
get_target_property(_sv_core_definitions shadowvol COMPILE_DEFINITIONS)
add_library(shadowvol_shared SHARED ${_sv_core_sources})
set_target_properties(shadowvol_shared PROPERTIES
  OUTPUT_NAME shadowvol
  VERSION ${PROJECT_VERSION}
  SOVERSION ${PROJECT_VERSION_MAJOR}
  POSITION_INDEPENDENT_CODE ON
  # The kernels and the C are exported; the C++ runtime is linked statically
  # into nothing: the .so needs libstdc++ like any C++ library.
  LINKER_LANGUAGE CXX)
if(_sv_core_options)
  target_compile_options(shadowvol_shared PRIVATE ${_sv_core_options})
endif()
if(_sv_core_definitions)
  target_compile_definitions(shadowvol_shared PRIVATE ${_sv_core_definitions})
endif()
target_include_directories(shadowvol_shared PUBLIC
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
# The planner's generated character (src/plan/planner.cpp).
target_include_directories(shadowvol_shared PRIVATE ${PROJECT_SOURCE_DIR}/src/modelgen)
# The object-level link check: a shared library must have no undefined
# symbol that the libraries it names do not provide.
target_link_options(shadowvol_shared PRIVATE -Wl,--no-undefined)

# The static library's include directory: the source tree's in the build,
# the prefix's once installed (an exported target may name no source path).
set_property(TARGET shadowvol PROPERTY INTERFACE_INCLUDE_DIRECTORIES
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)

# A C program that links the static library needs the C++ runtime (mesh
# preparation, std::vector in shadowvol_mesh.h) and libm.
set(SV_STATIC_LINK_LIBS stdc++ m)
set_property(TARGET shadowvol APPEND PROPERTY INTERFACE_LINK_LIBRARIES
  $<INSTALL_INTERFACE:stdc++> $<INSTALL_INTERFACE:m>)

install(FILES include/shadowvol.h include/shadowvol_mesh.h include/shadowvol_casters.h
              include/shadowvol_planes.h include/shadowvol_skin.h
              include/shadowvol_plan.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS shadowvol shadowvol_shared EXPORT shadowvolTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
set(_sv_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/shadowvol)
install(EXPORT shadowvolTargets NAMESPACE shadowvol:: DESTINATION ${_sv_cmake_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/shadowvolConfig.cmake.in
  ${PROJECT_BINARY_DIR}/shadowvolConfig.cmake INSTALL_DESTINATION ${_sv_cmake_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/shadowvolConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/shadowvolConfig.cmake
              ${PROJECT_BINARY_DIR}/shadowvolConfigVersion.cmake
        DESTINATION ${_sv_cmake_dir})

# pkg-config: paths relative to the .pc file's prefix, so a package moved
# after installation (or installed with DESTDIR) still resolves.
# (The .pc lies in LIBDIR/pkgconfig: as many ".." as LIBDIR has parts, plus one.)
string(REPLACE "/" ";" _sv_libdir_parts "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
set(SV_PC_PREFIX_FROM_PCFILEDIR "")
foreach(_part IN LISTS _sv_libdir_parts)
  string(APPEND SV_PC_PREFIX_FROM_PCFILEDIR "/..")
endforeach()
list(TRANSFORM SV_STATIC_LINK_LIBS PREPEND "-l" OUTPUT_VARIABLE _sv_private)
string(JOIN " " SV_PC_LIBS_PRIVATE ${_sv_private})
configure_file(${PROJECT_SOURCE_DIR}/cmake/shadowvol.pc.in
               ${PROJECT_BINARY_DIR}/shadowvol.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/shadowvol.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
