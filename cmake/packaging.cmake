# SPDX-License-Identifier: Apache-2.0
# Installation and the CMake package (native scope only).
#
#   cmake --install build/<preset> --prefix /opt/palp
#
# installs, under the prefix:
#   lib/libpalp_{analysis,recording,device,experiments}.a,           the SDK and what it links
#   libpalp_protocol.a, libpalp_protocol_text.a                      (PALP_SHARED=ON: the palp_*
#                                                                    SDK libraries as .so.0)
#   lib/pkgconfig/palp.pc, palp-analysis.pc                          pkg-config: the whole SDK;
#                                                                    analysis + recording alone
#   lib/libpalp_hdf5.a, include/palp/hdf5.hpp                        palp::hdf5, when it was built
#                                                                    (HDF5 found): palpConfig then
#                                                                    finds HDF5 for it
#   include/palp/*.hpp, include/palp/protocol/*.hpp                  (host/include, protocol/include)
#   lib/cmake/palp/palpConfig.cmake (+ version, targets)             find_package(palp) -> palp::sdk,
#                                                                    palp::analysis, ::recording,
#                                                                    ::device, ::experiments
#   lib/libpalp_sim*.a, libpalp_plant.a, libpalp_fw_core.a,          palp-sim linked in:
#   lib/palp-objects/ (palp_sim_inproc), include/palp/{sim,plant,fw}  palp::sim_inproc
#   bin/palpctl, bin/palp-sim                                        the tools
#   lib/udev/rules.d/70-palp.rules                                   so a non-root user can open
#                                                                    the controller (udev reads
#                                                                    /usr/lib/udev/rules.d; with
#                                                                    another prefix, copy it to
#                                                                    /etc/udev/rules.d)
# Components: "sdk" (libraries, headers, package files) and "tools" (binaries, udev rules); an
# install without --component installs both.
if(NOT PALP_SCOPE STREQUAL "native" OR NOT TARGET palp_sdk)
  return()
endif()

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PALP_NLOHMANN_JSON_MIN 3.10)  # as host/CMakeLists.txt asks for
set(PALP_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/palp CACHE STRING
    "Where palpConfig.cmake is installed, relative to the prefix")
# Not CMAKE_INSTALL_LIBDIR: udev looks in lib/udev/rules.d, never in a multiarch directory.
set(PALP_UDEV_RULES_DIR lib/udev/rules.d CACHE STRING
    "Where the udev rules are installed, relative to the prefix")

# An exported target may not carry a source-tree include path. The protocol libraries were
# declared with plain paths (they are also built for the firmware, which installs nothing), so
# those paths are split here into their build-tree form and the installed include directory.
# Paths already written with $<BUILD_INTERFACE:...> (as palp_sdk's are) are left alone.
function(palp_exportable_includes target)
  get_target_property(dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
  if(NOT dirs OR dirs MATCHES "BUILD_INTERFACE")
    return()
  endif()
  set(fixed)
  foreach(d IN LISTS dirs)
    list(APPEND fixed "$<BUILD_INTERFACE:${d}>")
  endforeach()
  list(APPEND fixed "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
  set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${fixed}")
endfunction()
palp_exportable_includes(palp_protocol)
palp_exportable_includes(palp_protocol_text)

foreach(lib sdk analysis recording device experiments)
  set_target_properties(palp_${lib} PROPERTIES EXPORT_NAME ${lib})
endforeach()
set_target_properties(palp_protocol PROPERTIES EXPORT_NAME protocol)
set_target_properties(palp_protocol_text PROPERTIES EXPORT_NAME protocol_text)

install(TARGETS palp_sdk palp_analysis palp_recording palp_device palp_experiments palp_protocol
                palp_protocol_text
        EXPORT palpTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT sdk
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT sdk)  # PALP_SHARED=ON
# The reports (palp/report.hpp, docs/report.md): palp::report, and the SVG renderer that
# write_report_svgs finds in <prefix>/share/palp/ beside <prefix>/bin/ (host/src/report/svg.cpp)
if(TARGET palp_report)
  set_target_properties(palp_report PROPERTIES EXPORT_NAME report)
  install(TARGETS palp_report EXPORT palpTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT sdk
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT sdk)
  install(FILES ${PROJECT_SOURCE_DIR}/host/report/vega-to-svg.js
          DESTINATION ${CMAKE_INSTALL_DATADIR}/palp COMPONENT tools)
endif()
# palp-sim linked in (component sim_inproc): palp/sim_inproc.hpp and sim+inproc:// URIs for a
# lab's own tests and CI, with the simulator's libraries under it (the real firmware core, the
# plant with its shipped phantoms built in, the robot bridge emulator). palp_sim_inproc is an
# OBJECT library (its URI registration must reach the program), installed as objects.
set(PALP_SIM_EXPORTS sim_inproc sim_server sim sim_io sim_robot plant fw_core)
if(TARGET palp_sim_inproc)
  foreach(lib IN LISTS PALP_SIM_EXPORTS)
    palp_exportable_includes(palp_${lib})
    set_target_properties(palp_${lib} PROPERTIES EXPORT_NAME ${lib})
  endforeach()
  list(TRANSFORM PALP_SIM_EXPORTS PREPEND palp_ OUTPUT_VARIABLE palp_sim_targets)
  install(TARGETS ${palp_sim_targets}
          EXPORT palpTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT sdk
          OBJECTS DESTINATION ${CMAKE_INSTALL_LIBDIR}/palp-objects COMPONENT sdk)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/host/sim_inproc/include/ ${PROJECT_SOURCE_DIR}/hil/sim/include/
                    ${PROJECT_SOURCE_DIR}/hil/plant/include/ ${PROJECT_SOURCE_DIR}/firmware/core/include/
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT sdk
          FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h")
endif()

# palp::hdf5 (palp/hdf5.hpp), only when it was built: an install without HDF5 has neither the
# library nor its header, and its palpConfig never looks for HDF5 (PALP_INSTALL_HDF5).
set(PALP_INSTALL_HDF5 FALSE)
set(palp_hdf5_header_rule PATTERN "hdf5.hpp" EXCLUDE)
if(TARGET palp_hdf5)
  set_target_properties(palp_hdf5 PROPERTIES EXPORT_NAME hdf5)
  install(TARGETS palp_hdf5 EXPORT palpTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT sdk
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT sdk)
  set(PALP_INSTALL_HDF5 TRUE)
  set(palp_hdf5_header_rule)
  # the libraries FindHDF5 gave the build (an INTERFACE target): palpConfig makes the same target
  # from them, as FindHDF5 cannot run in a consumer that enables no C
  get_target_property(PALP_HDF5_LINK_LIBRARIES HDF5::HDF5 INTERFACE_LINK_LIBRARIES)
endif()

install(DIRECTORY ${PROJECT_SOURCE_DIR}/host/include/ ${PROJECT_SOURCE_DIR}/protocol/include/
                  ${PROJECT_SOURCE_DIR}/protocol/host/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT sdk
        FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h" ${palp_hdf5_header_rule})
install(EXPORT palpTargets NAMESPACE palp:: DESTINATION ${PALP_INSTALL_CMAKEDIR} COMPONENT sdk)

# pkg-config: palp.pc (palp::sdk) and palp-analysis.pc (analysis + recording), relocatable
# (prefix from ${pcfiledir}). Static libraries need their link dependencies on every link, so
# palp.pc lists libusb, hidapi and libmodbus in Requires; shared ones in Requires.private.
set(PALP_PKGCONFIG_DIR ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
file(RELATIVE_PATH PALP_PC_TO_PREFIX /prefix/${PALP_PKGCONFIG_DIR} /prefix)
string(REGEX REPLACE "/$" "" PALP_PC_TO_PREFIX "${PALP_PC_TO_PREFIX}")
set(PALP_PC_REQUIRES "Requires: palp-analysis = ${PROJECT_VERSION}")
if(PALP_SHARED)
  string(APPEND PALP_PC_REQUIRES "\nRequires.private: libusb-1.0 hidapi-hidraw libmodbus")
else()
  string(APPEND PALP_PC_REQUIRES " libusb-1.0 hidapi-hidraw libmodbus")
endif()
foreach(pc palp palp-analysis)
  configure_file(${CMAKE_CURRENT_LIST_DIR}/${pc}.pc.in ${PROJECT_BINARY_DIR}/${pc}.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/${pc}.pc DESTINATION ${PALP_PKGCONFIG_DIR} COMPONENT sdk)
endforeach()

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/palpConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/palpConfig.cmake
                              INSTALL_DESTINATION ${PALP_INSTALL_CMAKEDIR}
                              PATH_VARS CMAKE_INSTALL_BINDIR)
# Before 1.0 a minor version may break the API (DESIGN.md: major = breaking once released).
write_basic_package_version_file(${PROJECT_BINARY_DIR}/palpConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/palpConfig.cmake ${PROJECT_BINARY_DIR}/palpConfigVersion.cmake
        DESTINATION ${PALP_INSTALL_CMAKEDIR} COMPONENT sdk)

foreach(tool palpctl palp-sim)
  if(TARGET ${tool})
    install(TARGETS ${tool} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tools)
  endif()
endforeach()
# OPTIONAL: the rules file may not exist yet in this checkout; the install skips it then.
install(FILES ${PROJECT_SOURCE_DIR}/host/udev/70-palp.rules
        DESTINATION ${PALP_UDEV_RULES_DIR} COMPONENT tools OPTIONAL)
# udev reads /usr/lib/udev/rules.d and /etc/udev/rules.d only: an install under another prefix
# says where to copy the rules (the .deb installs to /usr and needs nothing)
if(EXISTS ${PROJECT_SOURCE_DIR}/host/udev/70-palp.rules)
  install(CODE "
    if(NOT CMAKE_INSTALL_PREFIX STREQUAL \"/usr\")
      message(STATUS \"udev does not read \${CMAKE_INSTALL_PREFIX}/${PALP_UDEV_RULES_DIR}: to let the seat's user open the controller, run\\n\"
                     \"  sudo cp \${CMAKE_INSTALL_PREFIX}/${PALP_UDEV_RULES_DIR}/70-palp.rules /etc/udev/rules.d/ && sudo udevadm control --reload && sudo udevadm trigger\")
    endif()" COMPONENT tools)
endif()

include(${CMAKE_CURRENT_LIST_DIR}/deb.cmake)
