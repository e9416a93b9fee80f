# The libFuzzer harnesses of fuzz/ (issue 23) inside the default build: when a clang++ that can
# link `-fsanitize=fuzzer,address,undefined` is found, fuzz/ is configured and built with it as
# an ExternalProject in <build>/fuzz (the main build keeps its own compiler), and each harness
# gets a short smoke run in the default test suite (label `fuzz`). Without such a clang the
# build says so once, at configure time, and has no harnesses and no fuzz tests.
# `make fuzz` runs the long campaign (scripts/fuzz_campaign.sh); fuzz/README.md has the details.
include(ExternalProject)

# The one list of harnesses, fuzz/harnesses.txt (also read by fuzz/CMakeLists.txt and make fuzz).
file(READ ${PROJECT_SOURCE_DIR}/fuzz/harnesses.txt PLUMAGE_FUZZ_HARNESSES)
string(STRIP "${PLUMAGE_FUZZ_HARNESSES}" PLUMAGE_FUZZ_HARNESSES)
string(REPLACE " " ";" PLUMAGE_FUZZ_HARNESSES "${PLUMAGE_FUZZ_HARNESSES}")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/fuzz/harnesses.txt)

find_program(PLUMAGE_FUZZ_CXX NAMES clang++-14 clang++ DOC "clang++ for the libFuzzer harnesses")
if(PLUMAGE_FUZZ_CXX AND NOT DEFINED PLUMAGE_FUZZ_WORKS)
  # libFuzzer ships in a separate Debian package (libclang-rt-14-dev): try to link a harness.
  set(probe_dir ${PROJECT_BINARY_DIR}/CMakeFiles/fuzz-probe)
  file(WRITE ${probe_dir}/probe.cpp
       "#include <cstddef>\n#include <cstdint>\nextern \"C\" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }\n")
  execute_process(COMMAND ${PLUMAGE_FUZZ_CXX} -fsanitize=fuzzer,address,undefined ${probe_dir}/probe.cpp -o ${probe_dir}/probe
                  RESULT_VARIABLE probe_status OUTPUT_QUIET ERROR_QUIET)
  if(probe_status EQUAL 0)
    set(PLUMAGE_FUZZ_WORKS ON CACHE INTERNAL "clang++ links libFuzzer + ASan + UBSan")
  else()
    set(PLUMAGE_FUZZ_WORKS OFF CACHE INTERNAL "clang++ links libFuzzer + ASan + UBSan")
  endif()
endif()

if(NOT PLUMAGE_FUZZ_CXX OR NOT PLUMAGE_FUZZ_WORKS)
  message(STATUS "fuzz: no clang++ with libFuzzer (Debian: clang, libclang-rt-14-dev); "
                 "the fuzz harnesses and their smoke tests are skipped")
  return()
endif()
message(STATUS "fuzz: harnesses built with ${PLUMAGE_FUZZ_CXX} in ${PROJECT_BINARY_DIR}/fuzz")

set(fuzz_args -DCMAKE_CXX_COMPILER=${PLUMAGE_FUZZ_CXX})
if(CMAKE_CXX_COMPILER_LAUNCHER)
  list(APPEND fuzz_args -DCMAKE_CXX_COMPILER_LAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER})
endif()
ExternalProject_Add(plumage_fuzz
  SOURCE_DIR ${PROJECT_SOURCE_DIR}/fuzz
  BINARY_DIR ${PROJECT_BINARY_DIR}/fuzz
  CMAKE_ARGS ${fuzz_args}
  BUILD_ALWAYS ON  # its own make decides what is out of date (core sources are not tracked here)
  INSTALL_COMMAND "")

if(PLUMAGE_BUILD_TESTS)
  foreach(h IN LISTS PLUMAGE_FUZZ_HARNESSES)
    add_test(NAME fuzz_smoke_${h}
             COMMAND ${CMAKE_COMMAND} -DHARNESS=${h} -DFUZZ_BIN=${PROJECT_BINARY_DIR}/fuzz
                     -DFUZZ_SRC=${PROJECT_SOURCE_DIR}/fuzz -DSECONDS=3
                     -P ${PROJECT_SOURCE_DIR}/fuzz/smoke.cmake)
    set_tests_properties(fuzz_smoke_${h} PROPERTIES LABELS fuzz TIMEOUT 60)
  endforeach()
endif()
