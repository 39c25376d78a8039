# SPDX-License-Identifier: Apache-2.0
# Project code builds with -Wall -Wextra -Werror; third-party headers come in as system includes
# (CMake marks imported targets' include directories SYSTEM), so their warnings do not break it.
function(palp_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror -Wshadow -Wnon-virtual-dtor
                                           -Wcast-align)
endfunction()
