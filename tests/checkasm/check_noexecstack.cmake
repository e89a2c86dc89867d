# ctest -P script: the program named by BINARY must not ask for an executable
# stack (every NASM object emits .note.GNU-stack; a missing one would make
# the linker mark the whole program RWE).
execute_process(COMMAND readelf -lW ${BINARY} OUTPUT_VARIABLE out RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "readelf failed on ${BINARY}")
endif()
string(REGEX MATCH "GNU_STACK[^\n]*" line "${out}")
if(line STREQUAL "")
  message(FATAL_ERROR "${BINARY}: no GNU_STACK program header")
endif()
if(line MATCHES "RWE")
  message(FATAL_ERROR "${BINARY}: executable stack: ${line}")
endif()
message(STATUS "${BINARY}: ${line}")
