# SPDX-License-Identifier: Apache-2.0
# Runs one libFuzzer target for SECONDS (or RUNS executions, whichever comes first) from fresh
# seeds and the corpus it has grown so far, and writes its log to WORK/fuzz.log.
#   -DFUZZER=binary -DWORK=dir -DSECONDS=n [-DMAX_LEN=bytes]
#   seeds, any of: -DPROTO_TOOL=palp-proto -DVECTORS=protocol/vectors   (protocol frames)
#                  -DSEEDER=palp_fuzz_seeds -DDOCS=a.md|b.md             (fenced blocks of docs)
#                  -DSEEDER=palp_fuzz_seeds -DREGISTERS=robot_bridge.txt (register blocks)
#                  -DSEED_DIR=dir                                         (files as they are)
#   -DREGRESSIONS=dir: the inputs earlier campaigns found defects with, run first (when it exists)
# The environment overrides for a campaign (scripts/fuzz-campaign): PALP_FUZZ_SECONDS,
# PALP_FUZZ_RUNS (default: no limit). A crash leaves its input in WORK as crash-* and fails.
if(NOT EXISTS "${FUZZER}")
  message(FATAL_ERROR "fuzz target not built: ${FUZZER} is missing. Build it with "
                      "`cmake --preset clang-fuzz && cmake --build --preset clang-fuzz` "
                      "(scripts/test does this).")
endif()
if(DEFINED ENV{PALP_FUZZ_SECONDS})
  set(SECONDS $ENV{PALP_FUZZ_SECONDS})
endif()
set(runs -1)
if(DEFINED ENV{PALP_FUZZ_RUNS})
  set(runs $ENV{PALP_FUZZ_RUNS})
endif()
if(NOT MAX_LEN)
  set(MAX_LEN 4096)
endif()

# the findings of an earlier run go (a defect's input belongs in tests/fuzz/regressions)
file(GLOB earlier "${WORK}/crash-*" "${WORK}/leak-*" "${WORK}/timeout-*" "${WORK}/oom-*")
if(earlier)
  file(REMOVE ${earlier})
endif()
file(REMOVE_RECURSE "${WORK}/seeds")
file(MAKE_DIRECTORY "${WORK}/seeds" "${WORK}/corpus")
function(seed_step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_QUIET)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "could not write the fuzz seeds: ${ARGN}")
  endif()
endfunction()
if(PROTO_TOOL)
  seed_step("${PROTO_TOOL}" seeds "${VECTORS}" "${WORK}/seeds")
endif()
if(DOCS)
  string(REPLACE "|" ";" docs "${DOCS}")
  seed_step("${SEEDER}" docs "${WORK}/seeds" ${docs})
endif()
if(REGISTERS)
  seed_step("${SEEDER}" registers "${WORK}/seeds" "${REGISTERS}")
endif()
foreach(dir IN ITEMS "${SEED_DIR}" "${REGRESSIONS}")
  if(dir AND IS_DIRECTORY "${dir}")
    file(COPY "${dir}/" DESTINATION "${WORK}/seeds")
  endif()
endforeach()

execute_process(COMMAND "${FUZZER}" -max_total_time=${SECONDS} -runs=${runs} -timeout=10
                        -rss_limit_mb=2048 -max_len=${MAX_LEN} -print_final_stats=1
                        -artifact_prefix=${WORK}/ "${WORK}/corpus" "${WORK}/seeds"
                WORKING_DIRECTORY "${WORK}"
                OUTPUT_FILE "${WORK}/fuzz.log" ERROR_FILE "${WORK}/fuzz.log"
                RESULT_VARIABLE rc)
file(STRINGS "${WORK}/fuzz.log" done REGEX "(DONE|stat::number_of_executed_units|ERROR|SUMMARY)")
foreach(line IN LISTS done)
  message(STATUS "${line}")
endforeach()
if(NOT rc EQUAL 0)
  file(READ "${WORK}/fuzz.log" log)
  string(LENGTH "${log}" n)
  if(n GREATER 8000)
    math(EXPR from "${n} - 8000")
    string(SUBSTRING "${log}" ${from} -1 log)
  endif()
  message(FATAL_ERROR "fuzz target ${FUZZER} failed (exit ${rc}); the crashing input is in "
                      "${WORK} as crash-*; the end of its log (${WORK}/fuzz.log):\n${log}")
endif()
