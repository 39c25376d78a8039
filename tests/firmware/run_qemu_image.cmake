# SPDX-License-Identifier: Apache-2.0
# Runs a firmware test image on QEMU's mps2-an386 (Cortex-M4F) and passes only when QEMU exits
# with code 0 (the image's semihosting exit) and the image's UART output matches PASS_REGEX.
#
#   cmake -DIMAGE=<image.elf> -DPASS_REGEX=<regex> [-DVECTORS_DIR=<dir>] [-DHINT=<text>]
#         [-DICOUNT=ON] -P run_qemu_image.cmake
#
# The command line follows reference/qemu-icount.md: semihosting on (exit codes), UART0 on stdio
# (stdin is /dev/null, so QEMU never touches a terminal), no display, no monitor, and the whole
# run under `timeout 60`. The UART output is printed, so the test log shows the summary line.
# With VECTORS_DIR, every `vectors <file> sha256 <hex>` line the image prints must match that
# file now: an image built from other vectors fails with the command that rebuilds it.
# A missing image, qemu-system-arm or timeout is a failure, never a skip.
cmake_minimum_required(VERSION 3.25)

foreach(var IMAGE PASS_REGEX)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_qemu_image.cmake: -D${var}=... is required")
  endif()
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/find_qemu.cmake)

set(command "${TIMEOUT}" 60 "${QEMU}" -M mps2-an386 -display none -monitor none
            -semihosting-config enable=on,target=native -serial stdio -kernel "${IMAGE}")
if(ICOUNT)  # -DICOUNT=ON: one instruction per ns of virtual time, for instruction counts
  list(APPEND command -icount shift=0)
endif()
list(JOIN command " " command_text)
message(STATUS "${command_text}")

string(TIMESTAMP t0 "%s%f")
execute_process(COMMAND ${command} INPUT_FILE /dev/null OUTPUT_VARIABLE uart
                ERROR_VARIABLE qemu_stderr RESULT_VARIABLE rc)
string(TIMESTAMP t1 "%s%f")
math(EXPR ms "(${t1} - ${t0}) / 1000")

message(STATUS "UART output:\n${uart}")
message(STATUS "QEMU exit code ${rc} after ${ms} ms")
if(NOT qemu_stderr STREQUAL "")
  message(STATUS "QEMU stderr:\n${qemu_stderr}")
endif()

if(rc EQUAL 124)
  message(FATAL_ERROR "timed out after 60 s: the image neither finished nor faulted")
elseif(NOT rc EQUAL 0)
  message(FATAL_ERROR "QEMU exited with code ${rc} (1: a check failed, 3: an unexpected "
                      "exception; see the UART output above)")
endif()
if(NOT uart MATCHES "${PASS_REGEX}")
  message(FATAL_ERROR "the UART output has no line matching '${PASS_REGEX}'")
endif()

if(DEFINED VECTORS_DIR)
  string(REGEX MATCHALL "vectors [^ \n]+ sha256 [0-9a-f]+" announced "${uart}")
  if(NOT announced)
    message(FATAL_ERROR "the image names no vectors file (expected 'vectors <file> sha256 <hex>')")
  endif()
  foreach(item IN LISTS announced)
    string(REGEX REPLACE "^vectors ([^ ]+) sha256 ([0-9a-f]+)$" "\\1;\\2" item "${item}")
    list(GET item 0 name)
    list(GET item 1 built_from)
    file(SHA256 "${VECTORS_DIR}/${name}" now)
    if(NOT now STREQUAL built_from)
      message(FATAL_ERROR "${IMAGE} was built from another ${name} than "
                          "${VECTORS_DIR}/${name} holds now: ${HINT}")
    endif()
  endforeach()
endif()
