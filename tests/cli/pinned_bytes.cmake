# The bytes shadowvol writes today (issue 25, tools/pin_bytes.sh): every PNG
# of `shadowvol render` on each model in both modes, each volume's index
# list, and the demo scene's frames, against tests/cli/pinned_bytes.manifest.
# A difference prints "changed KEY OLD NEW" / "missing KEY" / "new KEY" and
# fails; an intended change regenerates the manifest in the same commit.
set(SV_PIN_BYTES ${PROJECT_SOURCE_DIR}/tools/pin_bytes.sh)

# Each entry works in its own folder under the build, kept after the run so
# a changed picture can be looked at.
#
# The bundled set runs in the sanitizer build too (Debug, -O0): the manifest
# is written from Release, so this entry shows that optimisation changes no
# byte. The shared models' set also matches there but takes several times
# longer, so it runs in Release only.
add_test(NAME pinned_bytes_bundled
  COMMAND ${SV_PIN_BYTES} --check ${CMAKE_BINARY_DIR} --set bundled
          --work ${CMAKE_CURRENT_BINARY_DIR}/pinned_bytes_bundled)

if(NOT SV_SANITIZE)
  add_test(NAME pinned_bytes_shared_models
    COMMAND ${SV_PIN_BYTES} --check ${CMAKE_BINARY_DIR} --set shared --models ${SV_SHARED_MODELS_DIR}
            --work ${CMAKE_CURRENT_BINARY_DIR}/pinned_bytes_shared_models)
  # Exit 77: no shared models folder here.
  set_tests_properties(pinned_bytes_shared_models PROPERTIES SKIP_RETURN_CODE 77)

  # The same bytes with dispatch held to the C kernels (the library's
  # volume and facing variants, skinning, planes, the rasteriser's row
  # kernels): one manifest holds an AVX2 machine and an AVX-512 one alike,
  # and depends on no one CPU's kernels.
  add_test(NAME pinned_bytes_bundled_isa_c
    COMMAND ${SV_PIN_BYTES} --check ${CMAKE_BINARY_DIR} --set bundled
            --work ${CMAKE_CURRENT_BINARY_DIR}/pinned_bytes_bundled_isa_c)
  set_tests_properties(pinned_bytes_bundled_isa_c PROPERTIES ENVIRONMENT "SV_ISA=c")
endif()
