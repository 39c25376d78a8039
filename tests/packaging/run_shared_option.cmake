# SPDX-License-Identifier: Apache-2.0
# cmake -P script behind the packaging_shared_option test (tests/packaging/CMakeLists.txt): a
# configure of this source tree with PALP_SHARED=ON in a scratch build directory (no build: a
# second build of the SDK is too slow for the test suite) succeeds, and the generated build links
# each SDK library as a shared library named libpalp_<name>.so.<version> with the SONAME
# libpalp_<name>.so.0.
cmake_minimum_required(VERSION 3.25)
foreach(v PALP_SOURCE_DIR PALP_VERSION WORK_DIR GENERATOR CXX_COMPILER C_COMPILER)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_shared_option.cmake needs -D${v}=...")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} -S ${PALP_SOURCE_DIR} -B ${WORK_DIR} -G ${GENERATOR}
                        -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_C_COMPILER=${C_COMPILER}
                        -DCMAKE_BUILD_TYPE=Release -DPALP_SHARED=ON --log-level=WARNING
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configure with PALP_SHARED=ON failed (${rc}):\n${out}\n${err}")
endif()
file(READ ${WORK_DIR}/build.ninja ninja)
foreach(lib analysis recording device experiments)
  string(REGEX MATCH "build host/libpalp_${lib}\\.so\\.${PALP_VERSION}[^\n]*\n(  [^\n]*\n)*  SONAME = ([^\n]*)" _ "${ninja}")
  if(NOT CMAKE_MATCH_2 STREQUAL "libpalp_${lib}.so.0")
    message(FATAL_ERROR "PALP_SHARED=ON does not link host/libpalp_${lib}.so.${PALP_VERSION} with the SONAME libpalp_${lib}.so.0 (found: '${CMAKE_MATCH_2}')")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})
message(STATUS "PALP_SHARED=ON configures libpalp_{analysis,recording,device,experiments}.so.${PALP_VERSION}, SONAME .so.0")
