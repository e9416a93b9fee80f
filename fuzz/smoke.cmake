# One harness's smoke run (ctest fuzz_smoke_<harness>, cmake/PlumageFuzz.cmake): every seed of
# fuzz/corpus/<harness> and every past finding of fuzz/regressions/<harness>, then SECONDS of
# fuzzing from them. New corpus entries and artifacts go to a scratch folder in the build tree,
# never into the checked-in corpus. libFuzzer exits non-zero on any finding (crash, sanitizer
# report, uncaught exception, leak, an input over 20 s), which fails the test.
set(scratch ${FUZZ_BIN}/smoke/${HARNESS})
file(REMOVE_RECURSE ${scratch})
file(MAKE_DIRECTORY ${scratch}/corpus)
set(dirs ${scratch}/corpus ${FUZZ_SRC}/corpus/${HARNESS})
if(IS_DIRECTORY ${FUZZ_SRC}/regressions/${HARNESS})
  list(APPEND dirs ${FUZZ_SRC}/regressions/${HARNESS})
endif()
execute_process(COMMAND ${FUZZ_BIN}/fuzz_${HARNESS} ${dirs}
                        -max_total_time=${SECONDS} -timeout=20 -rss_limit_mb=2048 -detect_leaks=1
                        -print_final_stats=1 -artifact_prefix=${scratch}/
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  file(GLOB found ${scratch}/crash-* ${scratch}/leak-* ${scratch}/timeout-* ${scratch}/oom-*)
  message(FATAL_ERROR "fuzz_${HARNESS}: finding (exit ${status}): ${found}\n"
                      "Reproduce: ${FUZZ_BIN}/fuzz_${HARNESS} <file>; fix the reader, then add the "
                      "input to fuzz/regressions/${HARNESS}/")
endif()
