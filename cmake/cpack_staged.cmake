# SPDX-License-Identifier: Apache-2.0
# CPack's project config file (cmake/deb.cmake), read by cpack after CPackConfig.cmake. When the
# environment names a staged install, PALP_CPACK_STAGED_DIR (a `cmake --install` under DESTDIR,
# so that it holds usr/...), the package is made of that tree as it is, instead of cpack
# installing the build tree itself, which first builds every target (its preinstall step). The
# packaging_deb test (tests/packaging) uses it: the test must not rebuild.
if(DEFINED ENV{PALP_CPACK_STAGED_DIR})
  set(CPACK_INSTALL_CMAKE_PROJECTS "")
  set(CPACK_INSTALLED_DIRECTORIES "$ENV{PALP_CPACK_STAGED_DIR};.")  # usr/... as it is
endif()
