# SPDX-License-Identifier: Apache-2.0
# cmake -P script behind the packaging_consumer test (tests/packaging/CMakeLists.txt).
#   1. cmake --install PALP_BUILD_DIR --prefix WORK_DIR/prefix   (every component)
#   2. the installed tree holds the libraries, headers, package files, tools and udev rules
#   3. configure + build consumer/ with CMAKE_PREFIX_PATH=the prefix, run it, check its output
#   4. the same for sim_consumer/: palp::sim_inproc, a sim+inproc:// URI, a hold on the simulator
#   5. when the install has palp::hdf5: hdf5_consumer/ writes and reads an HDF5 recording
cmake_minimum_required(VERSION 3.25)
foreach(v PALP_SOURCE_DIR PALP_BUILD_DIR PALP_VERSION CONSUMER_SOURCE SIM_CONSUMER_SOURCE WORK_DIR
        GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_consumer.cmake needs -D${v}=...")
  endif()
endforeach()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

step("install" ${CMAKE_COMMAND} --install ${PALP_BUILD_DIR} --prefix ${prefix})

# GNUInstallDirs may pick lib or lib64 or a multiarch lib/<triple>
file(GLOB_RECURSE config_file ${prefix}/*/palpConfig.cmake)
if(NOT config_file)
  message(FATAL_ERROR "no palpConfig.cmake under ${prefix}")
endif()
foreach(f bin/palpctl bin/palp-sim include/palp/probe.hpp include/palp/transport.hpp
          include/palp/protocol/messages.hpp include/palp/protocol/catalogue.hpp)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "the install lacks ${f}")
  endif()
endforeach()
if(EXISTS ${PALP_SOURCE_DIR}/host/udev/70-palp.rules AND
   NOT EXISTS ${prefix}/lib/udev/rules.d/70-palp.rules)
  message(FATAL_ERROR "the install lacks lib/udev/rules.d/70-palp.rules")
endif()
file(GLOB_RECURSE libs ${prefix}/*/libpalp_analysis.a ${prefix}/*/libpalp_device.a
     ${prefix}/*/libpalp_experiments.a ${prefix}/*/libpalp_protocol.a)
list(LENGTH libs nlibs)
if(NOT nlibs EQUAL 4)
  message(FATAL_ERROR "expected libpalp_{analysis,device,experiments}.a and libpalp_protocol.a under ${prefix}, found: ${libs}")
endif()

step("consumer configure" ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${WORK_DIR}/consumer
     -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix}
     -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_BUILD_TYPE=Release)
step("consumer build" ${CMAKE_COMMAND} --build ${WORK_DIR}/consumer)
step("consumer run" ${WORK_DIR}/consumer/consumer)

foreach(expect "sdk ${PALP_VERSION}" "uri host=127.0.0.1 port=7070 sim_tcp=1" "protocol ")
  string(FIND "${step_output}" "${expect}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "consumer output lacks \"${expect}\":\n${step_output}")
  endif()
endforeach()
message(STATUS "consumer built against ${prefix} and ran:\n${step_output}")

step("sim consumer configure" ${CMAKE_COMMAND} -S ${SIM_CONSUMER_SOURCE} -B ${WORK_DIR}/sim_consumer
     -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix}
     -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_BUILD_TYPE=Release)
step("sim consumer build" ${CMAKE_COMMAND} --build ${WORK_DIR}/sim_consumer)
step("sim consumer run" ${WORK_DIR}/sim_consumer/sim_consumer)
foreach(expect "board palp-sim serial SIM-0001" "hold ended completed")
  string(FIND "${step_output}" "${expect}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "sim_consumer output lacks \"${expect}\":\n${step_output}")
  endif()
endforeach()
message(STATUS "sim_consumer built against ${prefix} and ran:\n${step_output}")

# palp::hdf5, installed only by a build that found HDF5
file(GLOB_RECURSE hdf5_lib ${prefix}/*/libpalp_hdf5.a)
if(hdf5_lib)
  if(NOT EXISTS ${prefix}/include/palp/hdf5.hpp)
    message(FATAL_ERROR "the install has libpalp_hdf5.a but not include/palp/hdf5.hpp")
  endif()
  set(hdf5_source ${CONSUMER_SOURCE}/../hdf5_consumer)
  step("hdf5 consumer configure" ${CMAKE_COMMAND} -S ${hdf5_source} -B ${WORK_DIR}/hdf5_consumer
       -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix}
       -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_BUILD_TYPE=Release)
  step("hdf5 consumer build" ${CMAKE_COMMAND} --build ${WORK_DIR}/hdf5_consumer)
  step("hdf5 consumer run" ${WORK_DIR}/hdf5_consumer/hdf5_consumer ${WORK_DIR}/run.h5)
  string(FIND "${step_output}" "hdf5 recording rows 3 z_mm[2] 0.50" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "hdf5_consumer output lacks the recording read back:\n${step_output}")
  endif()
  message(STATUS "hdf5_consumer built against ${prefix} and ran:\n${step_output}")
elseif(EXISTS ${prefix}/include/palp/hdf5.hpp)
  message(FATAL_ERROR "the install has include/palp/hdf5.hpp without libpalp_hdf5.a")
endif()
