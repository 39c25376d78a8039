# SPDX-License-Identifier: Apache-2.0
# Project code builds with -Wall -Wextra -Werror; third-party headers come in as system includes
# (CMake marks imported targets' include directories SYSTEM), so their warnings do not break it.
# GCC 12 at -O3 (CMake's Release, a build without a preset) reports false -Wrestrict inside
# libstdc++'s inlined std::string operator+ (GCC bugs 105329 and 105651, fixed in GCC 13): there
# it stays a warning instead of an error, so `cmake -DCMAKE_BUILD_TYPE=Release` builds on Debian 12.
function(palp_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror -Wshadow -Wnon-virtual-dtor
                                           -Wcast-align)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_GREATER_EQUAL 12
     AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-error=restrict)
  endif()
endfunction()
