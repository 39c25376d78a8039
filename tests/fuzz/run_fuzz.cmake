# Runs one libFuzzer target for SECONDS, seeded from the golden vectors.
# -DFUZZER=binary -DPROTO_TOOL=palp-proto -DVECTORS=dir -DWORK=dir -DSECONDS=n
if(NOT EXISTS "${FUZZER}")
  message(FATAL_ERROR "fuzz target not built: ${FUZZER} is missing. Build it with "
                      "`cmake --preset clang-fuzz && cmake --build --preset clang-fuzz` "
                      "(scripts/test does this).")
endif()
file(REMOVE_RECURSE "${WORK}/seeds")
file(MAKE_DIRECTORY "${WORK}/seeds" "${WORK}/corpus")
execute_process(COMMAND "${PROTO_TOOL}" seeds "${VECTORS}" "${WORK}/seeds"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "could not write the fuzz seeds from ${VECTORS}")
endif()
execute_process(COMMAND "${FUZZER}" -max_total_time=${SECONDS} -timeout=10 -rss_limit_mb=2048
                        -max_len=4096 -print_final_stats=1 -artifact_prefix=${WORK}/
                        "${WORK}/corpus" "${WORK}/seeds"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz target ${FUZZER} failed (exit ${rc}); the crashing input is in the "
                      "working directory as crash-*")
endif()
