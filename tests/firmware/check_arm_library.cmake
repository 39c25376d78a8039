# SPDX-License-Identifier: Apache-2.0
# Checks that a static library was cross-compiled for the Cortex-M4F: every object is 32-bit
# little-endian ARM (objdump -f: elf32-littlearm, armv7e-m), built for ARMv7E-M with the
# single-precision FPU and the hard-float calling convention (readelf -A).
#
#   cmake -DLIBRARY=<lib.a> [-DHINT=<text>] -P check_arm_library.cmake
#
# A missing library or tool is a failure, never a skip.
cmake_minimum_required(VERSION 3.25)

if(NOT DEFINED HINT)
  set(HINT "")
endif()
if(NOT DEFINED LIBRARY)
  message(FATAL_ERROR "check_arm_library.cmake: -DLIBRARY=... is required")
endif()
find_program(OBJDUMP arm-none-eabi-objdump)
find_program(READELF arm-none-eabi-readelf)
if(NOT OBJDUMP OR NOT READELF)
  message(FATAL_ERROR "arm-none-eabi-objdump/readelf not found: run scripts/install-deps "
                      "(package gcc-arm-none-eabi, which brings binutils-arm-none-eabi)")
endif()
if(NOT EXISTS "${LIBRARY}")
  message(FATAL_ERROR "${LIBRARY} does not exist: ${HINT}")
endif()

execute_process(COMMAND "${OBJDUMP}" -f "${LIBRARY}" OUTPUT_VARIABLE formats
                ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${OBJDUMP} -f ${LIBRARY} failed (${rc}): ${err}")
endif()
execute_process(COMMAND "${READELF}" -A "${LIBRARY}" OUTPUT_VARIABLE attributes
                ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${READELF} -A ${LIBRARY} failed (${rc}): ${err}")
endif()

# One count per object; each property must hold for all of them.
string(REGEX MATCHALL "file format [^\n]+" all_objects "${formats}")
list(LENGTH all_objects objects)
if(objects EQUAL 0)
  message(FATAL_ERROR "${LIBRARY} has no objects")
endif()

set(failed FALSE)
macro(require text pattern what)
  string(REGEX MATCHALL "${pattern}" hits "${text}")
  list(LENGTH hits n)
  if(NOT n EQUAL objects)
    message(SEND_ERROR "${n} of ${objects} objects are ${what} ('${pattern}')")
    set(failed TRUE)
  else()
    message(STATUS "${objects} of ${objects} objects are ${what}")
  endif()
endmacro()
require("${formats}" "file format elf32-littlearm" "32-bit little-endian ARM ELF")
require("${formats}" "architecture: armv7e-m" "ARMv7E-M (Cortex-M4)")
require("${attributes}" "Tag_CPU_arch: v7E-M\n" "built for Tag_CPU_arch v7E-M")
require("${attributes}" "Tag_CPU_arch_profile: Microcontroller" "M-profile")
require("${attributes}" "Tag_FP_arch: VFPv4-D16" "built for the FPv4-SP-D16 FPU")
require("${attributes}" "Tag_ABI_VFP_args: VFP registers" "hard-float ABI")
if(failed)
  message(FATAL_ERROR "${LIBRARY} is not (entirely) a Cortex-M4F library")
endif()
message(STATUS "${LIBRARY}: ${objects} Cortex-M4F objects")
