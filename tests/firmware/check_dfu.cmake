# SPDX-License-Identifier: Apache-2.0
# The STM32 image's .dfu checked by dfu-util's own tools (Debian's dfu-util 0.11 package):
#   dfu-suffix --check  exits 0 and shows 0483:df11, bcdDFU 0x011A, length 16
#   dfuse-pack --dump   one target with one element at 0x08000000 whose dumped bytes equal the
#                       .bin, and no "CRC ERROR" / "PARSE ERROR" (it exits 0 even then: the text
#                       is what is checked)
# and the same file with one byte flipped inside the element: dfu-suffix --check fails and
# dfuse-pack prints CRC ERROR (so this test can fail).
#   cmake -DDFU=<.dfu> -DBIN=<.bin> -DWORK_DIR=<dir> -DOBJCOPY=<objcopy> -DHINT=<how to build>
#         -P check_dfu.cmake
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/image_edit.cmake)

foreach(f DFU BIN)
  if(NOT EXISTS "${${f}}")
    message(FATAL_ERROR "${${f}} does not exist: ${HINT}")
  endif()
endforeach()
find_program(DFU_SUFFIX dfu-suffix)
find_program(DFUSE_PACK dfuse-pack)
if(NOT DFU_SUFFIX OR NOT DFUSE_PACK)
  message(FATAL_ERROR "dfu-suffix or dfuse-pack not found: run scripts/install-deps "
                      "(apt-get install dfu-util)")
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(good "${WORK_DIR}/image.dfu")
configure_file("${DFU}" "${good}" COPYONLY)  # dfuse-pack --dump writes next to the file
file(SIZE "${BIN}" bin_size)
set(failures "")

# ---- the good file ---------------------------------------------------------------------------
execute_process(COMMAND ${DFU_SUFFIX} --check "${good}" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE out)
foreach(line "Product ID:\t0xDF11" "Vendor ID:\t0x0483" "BCD DFU:\t0x011A" "Length:\t\t16")
  string(FIND "${out}" "${line}" at)
  if(at EQUAL -1)
    list(APPEND failures "dfu-suffix --check does not show '${line}'")
  endif()
endforeach()
if(NOT rc EQUAL 0)
  list(APPEND failures "dfu-suffix --check exited ${rc}")
endif()
message(STATUS "dfu-suffix --check ${DFU}: exit ${rc}\n${out}")

execute_process(COMMAND ${DFUSE_PACK} --dump "${good}" WORKING_DIRECTORY "${WORK_DIR}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message(STATUS "dfuse-pack --dump ${DFU}: exit ${rc}\n${out}")
if(NOT out MATCHES "targets: 1\n")
  list(APPEND failures "dfuse-pack: not one target")
endif()
if(NOT out MATCHES "elements: 1\n  0, address: 0x08000000, size: ${bin_size}\n")
  list(APPEND failures "dfuse-pack: not one element of ${bin_size} bytes at 0x08000000")
endif()
if(NOT out MATCHES "usb: 0483:df11, device: 0xffff, dfu: 0x011a, b'UFD', 16, ")
  list(APPEND failures "dfuse-pack: the suffix is not 0483:df11 bcdDFU 0x011a")
endif()
if(out MATCHES "CRC ERROR|PARSE ERROR")
  list(APPEND failures "dfuse-pack reports an error on the built .dfu")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${good}.target0.image0.bin" "${BIN}"
                RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  list(APPEND failures "the element dfuse-pack dumped differs from ${BIN}")
endif()

# ---- one byte flipped inside the element (past the 293-byte prefix) ----------------------------
set(bad "${WORK_DIR}/flipped.dfu")
palp_test_flip_byte("${good}" "${bad}" 400 ${OBJCOPY})
execute_process(COMMAND ${DFU_SUFFIX} --check "${bad}" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE out)
if(rc EQUAL 0)
  list(APPEND failures "dfu-suffix --check accepts a .dfu with a flipped byte")
endif()
execute_process(COMMAND ${DFUSE_PACK} --dump "${bad}" WORKING_DIRECTORY "${WORK_DIR}"
                OUTPUT_VARIABLE out ERROR_VARIABLE out)
message(STATUS "dfuse-pack --dump of the flipped copy:\n${out}")
if(NOT out MATCHES "CRC ERROR: computed crc32 is 0x")
  list(APPEND failures "dfuse-pack prints no CRC ERROR for a .dfu with a flipped byte")
endif()

if(failures)
  list(JOIN failures "\n  " text)
  message(FATAL_ERROR "${DFU}:\n  ${text}")
endif()
message(STATUS "${DFU}: dfu-suffix and dfuse-pack accept it; a flipped byte is caught by both")
