# SPDX-License-Identifier: Apache-2.0
# cmake -P script behind the packaging_deb test (tests/packaging/CMakeLists.txt): the .deb of
# cmake/deb.cmake, made and checked without changing anything on the machine and without a build.
#   1. cmake --install PALP_BUILD_DIR into WORK_DIR/stage (DESTDIR, prefix /usr), then cpack from
#      that staged tree (cmake/cpack_staged.cmake): palp_<version>_<arch>.deb
#   2. its control fields: Depends names the runtime libraries, Recommends the -dev packages
#   3. apt-get install -s (a simulation, no lock taken) resolves its dependencies on this machine
#   4. dpkg-deb -x unpacks it into WORK_DIR/root: the udev rules are where udev reads them
#   5. palpctl --version runs from the unpacked tree and says this version
#   6. consumer/ (find_package(palp), CMAKE_PREFIX_PATH=WORK_DIR/root/usr) builds and runs
#   7. pkg-config --cflags --libs palp-analysis and palp from the unpacked tree build the
#      analysis consumer and the consumer with a bare compiler command, and they run
#   8. /usr/bin/python3 -c 'import palp' with PYTHONPATH into the unpacked tree, when the package
#      has the Python module (the build's "python" component); else a note says it was not checked
cmake_minimum_required(VERSION 3.25)
foreach(v PALP_BUILD_DIR PALP_VERSION CONSUMER_SOURCE ANALYSIS_CONSUMER_SOURCE WORK_DIR GENERATOR
        CXX_COMPILER CPACK_COMMAND)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_deb.cmake needs -D${v}=...")
  endif()
endforeach()

file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
string(TIMESTAMP started "%s")
function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  string(TIMESTAMP now "%s")
  math(EXPR s "${now} - ${started}")
  message(STATUS "[${s} s] ${what}")
  set(step_output "${out}${err}" PARENT_SCOPE)
endfunction()
function(expect_in text what)
  foreach(e IN LISTS ARGN)
    string(FIND "${text}" "${e}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "${what} lacks \"${e}\":\n${text}")
    endif()
  endforeach()
endfunction()

# 1. the package, from a staged install (cpack's own install would build every target first)
step("staged install" ${CMAKE_COMMAND} -E env DESTDIR=${WORK_DIR}/stage
     ${CMAKE_COMMAND} --install ${PALP_BUILD_DIR} --prefix /usr)
step("cpack" ${CMAKE_COMMAND} -E env PALP_CPACK_STAGED_DIR=${WORK_DIR}/stage
     ${CPACK_COMMAND} --config ${PALP_BUILD_DIR}/CPackConfig.cmake -B ${WORK_DIR}/out)
file(GLOB deb ${WORK_DIR}/out/palp_${PALP_VERSION}_*.deb)
list(LENGTH deb ndeb)
if(NOT ndeb EQUAL 1)
  message(FATAL_ERROR "expected one palp_${PALP_VERSION}_<arch>.deb in ${WORK_DIR}/out, found: ${deb}")
endif()

# 2. the control fields
step("dpkg-deb --field" dpkg-deb --field ${deb} Package Version Depends Recommends)
expect_in("${step_output}" "the control file" "Package: palp" "Version: ${PALP_VERSION}"
          "libusb-1.0-0" "libhidapi-hidraw0" "libmodbus5" "Recommends:" "nlohmann-json3-dev")

# 3. the dependencies resolve (as root apt-get would lock dpkg even to simulate: no locking)
step("apt-get install -s" apt-get install -s -o Debug::NoLocking=1 ${deb})
expect_in("${step_output}" "apt-get's simulation" "Inst palp" "Conf palp")

# 4. unpacked: the tools, the SDK, the udev rules where udev reads them
set(root ${WORK_DIR}/root)
step("dpkg-deb -x" dpkg-deb -x ${deb} ${root})
foreach(f usr/bin/palpctl usr/bin/palp-sim usr/lib/udev/rules.d/70-palp.rules
          usr/include/palp/recording.hpp usr/lib/cmake/palp/palpConfig.cmake
          usr/lib/pkgconfig/palp.pc usr/lib/pkgconfig/palp-analysis.pc)
  if(NOT EXISTS ${root}/${f})
    message(FATAL_ERROR "the package lacks /${f}")
  endif()
endforeach()

# 5. palpctl from the package
step("palpctl --version" ${root}/usr/bin/palpctl --version)
expect_in("${step_output}" "palpctl --version" "${PALP_VERSION}")

# 6. an outside CMake project against the unpacked tree
step("consumer configure" ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${WORK_DIR}/consumer
     -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${root}/usr
     -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_BUILD_TYPE=Release)
step("consumer build" ${CMAKE_COMMAND} --build ${WORK_DIR}/consumer)
step("consumer run" ${WORK_DIR}/consumer/consumer)
expect_in("${step_output}" "the consumer's output" "sdk ${PALP_VERSION}")

# 7. pkg-config from the unpacked tree, and a bare compiler command
set(pc ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${root}/usr/lib/pkgconfig pkg-config)
foreach(pair "palp-analysis;${ANALYSIS_CONSUMER_SOURCE}/main.cpp;analysis;-lpalp_recording"
             "palp;${CONSUMER_SOURCE}/main.cpp;sdk;-lpalp_device")
  list(GET pair 0 module)
  list(GET pair 1 source)
  list(GET pair 2 name)
  list(GET pair 3 lib)
  step("pkg-config ${module}" ${pc} --cflags --libs ${module})
  string(STRIP "${step_output}" flags)
  # the prefix comes from the .pc file's own directory (relocatable)
  expect_in("${flags}" "pkg-config --libs ${module}" "-I${root}/usr/" "-L${root}/usr/" "${lib}")
  separate_arguments(flags UNIX_COMMAND "${flags}")
  step("${module}: c++ $(pkg-config --cflags --libs)" ${CXX_COMPILER} -std=c++20
       ${source} -o ${WORK_DIR}/pc_${name} ${flags})
endforeach()
step("pkg-config analysis consumer run" ${WORK_DIR}/pc_analysis ${WORK_DIR}/pc_run)
expect_in("${step_output}" "the analysis consumer's output" "hertz_N 0.210819"
          "recording rows 1002 i_A[250] 3.00 last rep 1 same 1")
step("pkg-config consumer run" ${WORK_DIR}/pc_sdk)
expect_in("${step_output}" "the consumer's output" "sdk ${PALP_VERSION}")

# 8. the Python module, when the package has it
set(site)
file(GLOB_RECURSE py_init ${root}/usr/lib/__init__.py)  # every __init__.py under usr/lib
list(FILTER py_init INCLUDE REGEX "/palp/__init__\\.py$")
file(GLOB_RECURSE py_ext ${root}/usr/lib/palp*.so)     # or a bare extension module palp.*.so
if(py_init)
  list(GET py_init 0 first)
  get_filename_component(pkg_dir ${first} DIRECTORY)
  get_filename_component(site ${pkg_dir} DIRECTORY)
elseif(py_ext)
  list(GET py_ext 0 first)
  get_filename_component(site ${first} DIRECTORY)
endif()
if(site)
  step("import palp" ${CMAKE_COMMAND} -E env PYTHONPATH=${site} /usr/bin/python3 -c
       "print('palp from', __import__('os').path.dirname(__import__('palp').__file__))")  # no ';': a CMake list
  expect_in("${step_output}" "import palp" "palp from ${site}")
else()
  message(STATUS "NOTE: the package has no Python module (this build has no \"python\" install "
                 "component): /usr/bin/python3 -c 'import palp' was not checked")
endif()
string(TIMESTAMP now "%s")
math(EXPR s "${now} - ${started}")
message(STATUS "packaging_deb: ${deb} made and checked in ${s} s")
