# SPDX-License-Identifier: Apache-2.0
# cmake -P script behind the packaging_analysis_only test (tests/packaging/CMakeLists.txt): an
# outside project links palp::analysis and palp::recording alone on a machine without the device
# libraries' dev packages, simulated by hiding every pkg-config module (PKG_CONFIG_LIBDIR = an empty directory).
#   1. cmake --install PALP_BUILD_DIR --component sdk --prefix WORK_DIR/prefix
#   2. with the modules hidden, find_package(palp) without components fails and names them; with
#      QUIET it fails without a word
#   3. with the modules hidden, analysis_consumer/ (COMPONENTS analysis recording) configures,
#      builds, runs and gives the known values (a recording written and read back among them),
#      and its executable needs none of libusb, hidapi, libmodbus
cmake_minimum_required(VERSION 3.25)
foreach(v PALP_BUILD_DIR CONSUMER_SOURCE FULL_CONSUMER_SOURCE WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_analysis_consumer.cmake needs -D${v}=...")
  endif()
endforeach()

set(prefix ${WORK_DIR}/prefix)
set(empty ${WORK_DIR}/no-pkg-config-modules)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${empty})

function(run out_rc what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(${out_rc} ${rc} PARENT_SCOPE)
  set(run_output "${out}${err}" PARENT_SCOPE)
endfunction()
set(hidden ${CMAKE_COMMAND} -E env PKG_CONFIG_LIBDIR=${empty} PKG_CONFIG_PATH=)
set(configure_args -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_BUILD_TYPE=Release)

run(rc "install" ${CMAKE_COMMAND} --install ${PALP_BUILD_DIR} --component sdk --prefix ${prefix})
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install failed (${rc}):\n${run_output}")
endif()

# the hiding works: the whole SDK cannot be found, and the message names the modules
run(rc "full configure" ${hidden} ${CMAKE_COMMAND} -S ${FULL_CONSUMER_SOURCE}
    -B ${WORK_DIR}/full ${configure_args})
if(rc EQUAL 0)
  message(FATAL_ERROR "find_package(palp) succeeded with the pkg-config modules hidden:\n${run_output}")
endif()
foreach(expect "libusb-1.0" "hidapi-hidraw" "libmodbus" "COMPONENTS analysis")
  string(FIND "${run_output}" "${expect}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the refusal does not name ${expect}:\n${run_output}")
  endif()
endforeach()

# QUIET: the same refusal prints nothing, and the project goes on without palp
file(WRITE ${WORK_DIR}/quiet/CMakeLists.txt "cmake_minimum_required(VERSION 3.25)
project(quiet LANGUAGES CXX)
find_package(palp 0.1 QUIET)
message(STATUS \"palp_FOUND=[\${palp_FOUND}]\")
")
run(rc "quiet configure" ${hidden} ${CMAKE_COMMAND} -S ${WORK_DIR}/quiet -B ${WORK_DIR}/quiet/build
    ${configure_args})
if(NOT rc EQUAL 0 OR NOT run_output MATCHES "palp_FOUND=\\[(0|FALSE)\\]")
  message(FATAL_ERROR "find_package(palp QUIET) with the modules hidden did not configure with palp_FOUND false (${rc}):\n${run_output}")
endif()
foreach(loud "libusb" "hidapi" "libmodbus" "Warning" "palp's")
  string(FIND "${run_output}" "${loud}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "find_package(palp QUIET) was not quiet (it says \"${loud}\"):\n${run_output}")
  endif()
endforeach()

run(rc "configure" ${hidden} ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${WORK_DIR}/consumer
    ${configure_args})
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "analysis consumer configure failed (${rc}):\n${run_output}")
endif()
run(rc "build" ${hidden} ${CMAKE_COMMAND} --build ${WORK_DIR}/consumer)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "analysis consumer build failed (${rc}):\n${run_output}")
endif()
run(rc "run" ${WORK_DIR}/consumer/analysis_consumer ${WORK_DIR}/run)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "analysis consumer run failed (${rc}):\n${run_output}")
endif()
foreach(expect "hertz_N 0.210819" "repetitions 2"
               "recording rows 1002 i_A[250] 3.00 last rep 1 same 1")
  string(FIND "${run_output}" "${expect}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "analysis consumer output lacks \"${expect}\":\n${run_output}")
  endif()
endforeach()
run(rc "readelf" readelf -d ${WORK_DIR}/consumer/analysis_consumer)
foreach(lib usb hidapi modbus)
  string(FIND "${run_output}" "lib${lib}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "analysis_consumer needs lib${lib}:\n${run_output}")
  endif()
endforeach()
foreach(f run.csv run.json)
  if(NOT EXISTS ${WORK_DIR}/${f})
    message(FATAL_ERROR "analysis_consumer wrote no ${f}")
  endif()
endforeach()
message(STATUS "palp::analysis and palp::recording alone built and ran with the device modules hidden")
