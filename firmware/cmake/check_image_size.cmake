# SPDX-License-Identifier: Apache-2.0
# Fails when a firmware image (or its .bin) is missing, or when its flash, RAM or CCM SRAM use
# exceeds a budget. Sizes are summed from `arm-none-eabi-size -A` (section name, size, address):
#   flash = every section stored in flash: those at 0x08000000.. plus the load images of .data and
#           .ccmram (copied at reset)
#   RAM   = sections at 0x20000000.. (stack, .data, .bss)
#   CCM   = sections at 0x10000000.. (.ccmram, .ccmram_bss)
#
#   cmake [-DSIZE=<arm-none-eabi-size>] -DIMAGE=<a.elf> [-DBIN=<a.bin>] -DFLASH_BUDGET=<bytes>
#         -DRAM_BUDGET=<bytes> -DCCM_BUDGET=<bytes> [-DHINT=<text>] -P check_image_size.cmake
# Run after the link of palp-stm32-bringup.elf (firmware/CMakeLists.txt) and by ctest
# (tests/firmware).
cmake_minimum_required(VERSION 3.25)

if(NOT DEFINED HINT)
  set(HINT "")
endif()
foreach(budget FLASH_BUDGET RAM_BUDGET CCM_BUDGET)
  if(NOT DEFINED ${budget} OR NOT ${budget} MATCHES "^[0-9]+$")
    message(FATAL_ERROR "check_image_size: -D${budget}=<bytes> is required (got '${${budget}}')")
  endif()
endforeach()
if(NOT DEFINED SIZE OR SIZE STREQUAL "")
  find_program(SIZE arm-none-eabi-size)
endif()
if(NOT SIZE)
  message(FATAL_ERROR "arm-none-eabi-size not found: run scripts/install-deps "
                      "(package gcc-arm-none-eabi, which brings binutils-arm-none-eabi)")
endif()
if(NOT EXISTS "${IMAGE}")
  message(FATAL_ERROR "firmware image ${IMAGE} does not exist: ${HINT}")
endif()
if(DEFINED BIN AND NOT EXISTS "${BIN}")
  message(FATAL_ERROR "flashable image ${BIN} does not exist: ${HINT}")
endif()

execute_process(COMMAND ${SIZE} -A -d "${IMAGE}" OUTPUT_VARIABLE table RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${SIZE} -A -d ${IMAGE} failed (${rc})")
endif()

set(flash 0)
set(ram 0)
set(ccm 0)
string(REPLACE "\n" ";" lines "${table}")
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^([.A-Za-z_][^ ]*) +([0-9]+) +([0-9]+)$")
    continue()
  endif()
  set(name ${CMAKE_MATCH_1})
  set(size ${CMAKE_MATCH_2})
  set(address ${CMAKE_MATCH_3})
  if(address GREATER_EQUAL 134217728 AND address LESS 268435456)      # 0x08000000..0x0FFFFFFF
    math(EXPR flash "${flash} + ${size}")
  elseif(address GREATER_EQUAL 536870912 AND address LESS 805306368)  # 0x20000000..0x2FFFFFFF
    math(EXPR ram "${ram} + ${size}")
  elseif(address GREATER_EQUAL 268435456 AND address LESS 285212672)  # 0x10000000..0x10FFFFFF
    math(EXPR ccm "${ccm} + ${size}")
  endif()
  if(name STREQUAL ".data" OR name STREQUAL ".ccmram")  # stored in flash too
    math(EXPR flash "${flash} + ${size}")
  endif()
endforeach()

get_filename_component(image_name "${IMAGE}" NAME)
message(STATUS "${image_name}: flash ${flash} of ${FLASH_BUDGET} B, RAM ${ram} of ${RAM_BUDGET} B, "
               "CCM ${ccm} of ${CCM_BUDGET} B")
set(over "")
foreach(region flash ram ccm)
  string(TOUPPER ${region} upper)
  if(${region} GREATER ${${upper}_BUDGET})
    list(APPEND over "${region} ${${region}} B > budget ${${upper}_BUDGET} B")
  endif()
endforeach()
if(over)
  string(REPLACE ";" ", " over "${over}")
  message(FATAL_ERROR "${image_name} is over budget: ${over}")
endif()
