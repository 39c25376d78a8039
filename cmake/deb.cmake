# SPDX-License-Identifier: Apache-2.0
# The Debian package (CPack's DEB generator), included by cmake/packaging.cmake:
#
#   cmake --build build/<preset> && cd build/<preset> && cpack     -> palp_<version>_<arch>.deb
#
# One package with every install component: the SDK (libraries, headers, CMake and pkg-config
# files), palpctl, palp-sim, the udev rules in /usr/lib/udev/rules.d, and the Python module when
# the build has it (component "python", python/): whatever is installed is packaged.
# Depends: the shared libraries the programs load, by their Debian 12 names. Recommends: what the
# SDK's headers and CMake package need to build against (the -dev packages), and what the reports
# and the live view read at run time (Vega, dygraphs, node). tests/packaging (packaging_deb)
# builds it from the installed tree without rebuilding and checks it against this machine.
#
# Deferred to the end of the top-level CMakeLists.txt, so the components of directories added
# after this file (python/) are known when the dependencies are chosen.
function(palp_deb_package)
  get_cmake_property(components COMPONENTS)
  set(depends libc6 libstdc++6 libgcc-s1 libusb-1.0-0 libhidapi-hidraw0 libmodbus5)
  set(recommends nlohmann-json3-dev libeigen3-dev libusb-1.0-0-dev libhidapi-dev libmodbus-dev
      pkg-config libjs-vega libjs-dygraphs nodejs node-vega)
  if(TARGET palp_hdf5)
    list(APPEND depends libhdf5-103-1)
    list(APPEND recommends libhdf5-dev)
  endif()
  if("python" IN_LIST components)
    # a compiled extension module: the minor version of Python it was built for, and numpy
    execute_process(COMMAND /usr/bin/python3 -c
                    "import sys; print(f'{sys.version_info[0]}.{sys.version_info[1]}')"
                    OUTPUT_VARIABLE py OUTPUT_STRIP_TRAILING_WHITESPACE)
    string(REGEX MATCH "^([0-9]+)\\.([0-9]+)$" _ "${py}")
    math(EXPR next_minor "${CMAKE_MATCH_2} + 1")
    list(APPEND depends "python3 (>= ${py})" "python3 (<< ${CMAKE_MATCH_1}.${next_minor})"
         python3-numpy)
    list(APPEND recommends python3-pandas)
  endif()
  list(JOIN depends ", " CPACK_DEBIAN_PACKAGE_DEPENDS)
  list(JOIN recommends ", " CPACK_DEBIAN_PACKAGE_RECOMMENDS)

  set(CPACK_GENERATOR DEB)
  set(CPACK_PACKAGE_NAME palp)
  set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
  set(CPACK_PACKAGE_CONTACT "palp maintainers <palp@localhost>")
  set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
      "${PROJECT_DESCRIPTION}: host SDK, palpctl, palp-sim, udev rules")
  set(CPACK_PACKAGE_DESCRIPTION
      "palp drives a voice-coil palpation probe on a robot arm. This package holds the C++ host SDK (libraries, headers, CMake and pkg-config files), the palpctl command-line tool, the palp-sim simulator and the udev rules that let the seat's user open the controller.")
  set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
  set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
  set(CPACK_DEB_COMPONENT_INSTALL OFF)  # one package, every component
  set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # palp_<version>_<arch>.deb
  set(CPACK_DEBIAN_PACKAGE_SECTION science)
  set(CPACK_DEBIAN_PACKAGE_LICENSE Apache-2.0)
  # cpack_staged.cmake: packaging_deb packages an installed tree as it is, without a build
  set(CPACK_PROJECT_CONFIG_FILE ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/cpack_staged.cmake)
  include(CPack)
endfunction()
cmake_language(DEFER DIRECTORY ${PROJECT_SOURCE_DIR} CALL palp_deb_package)
