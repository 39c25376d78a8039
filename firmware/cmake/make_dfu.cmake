# SPDX-License-Identifier: Apache-2.0
# Post-build: the DfuSe file (.dfu) of an STM32 image, for the ROM DFU bootloader and dfu-util.
#
#   cmake -DBIN=<image.bin> -DDFU=<image.dfu> -DOBJCOPY=<objcopy>
#         [-DADDRESS=0x08000000] [-DVID=0x0483] [-DPID=0xDF11] -P make_dfu.cmake
#
# Format (../shared/reference/usb-dfu-facts.md §6.2 container, §6.1 suffix), all little-endian:
#   prefix   "DfuSe", bVersion 1, DFUImageSize (the whole file, suffix included), bTargets 1
#   target   "Target", bAlternateSetting 0, bTargetNamed 1, szTargetName "Internal Flash"
#            (255 bytes, NUL-padded), dwTargetSize 8 + image, dwNbElements 1
#   element  dwElementAddress ADDRESS, dwElementSize = the .bin's size, then the .bin's bytes
#   suffix   bcdDevice 0xFFFF (any), idProduct PID, idVendor VID (the ROM bootloader's 0483:df11,
#            facts §5.7), bcdDFU 0x011A (DfuSe), "UFD", bLength 16, dwCRC: the CRC-32 state
#            (no final XOR) over every byte before dwCRC (facts §6.1)
# The prefix with the target and element headers, and the suffix, are written through Intel HEX
# (image_bytes.cmake); the file is `cmake -E cat` of those two around the .bin, untouched.
# Checked by Debian's dfu-suffix --check and dfuse-pack --dump (tests/firmware).
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/image_bytes.cmake)

foreach(var BIN DFU OBJCOPY)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "make_dfu.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT DEFINED ADDRESS)
  set(ADDRESS 0x08000000)  # the STM32G474's flash (stm32g474-facts.md §1.1)
endif()
if(NOT DEFINED VID)
  set(VID 0x0483)
endif()
if(NOT DEFINED PID)
  set(PID 0xDF11)
endif()
set(target_name "Internal Flash")

file(SIZE "${BIN}" image_size)
if(image_size EQUAL 0)
  message(FATAL_ERROR "${BIN} is empty")
endif()
math(EXPR element_bytes "8 + ${image_size}")
math(EXPR file_size "11 + 274 + ${element_bytes} + 16")

# ---- prefix, target prefix, element header --------------------------------------------------
string(HEX "DfuSe" head)
palp_le_hex(v ${file_size} 4)
string(APPEND head "01${v}01")
string(HEX "Target" h)
string(APPEND head "${h}00" "01000000")
string(HEX "${target_name}" name_hex)
string(LENGTH "${name_hex}" name_chars)
math(EXPR pad "255 - ${name_chars} / 2")
string(REPEAT "00" ${pad} zeros)
string(APPEND head "${name_hex}${zeros}")
palp_le_hex(v ${element_bytes} 4)
string(APPEND head "${v}01000000")
palp_le_hex(v ${ADDRESS} 4)
string(APPEND head "${v}")
palp_le_hex(v ${image_size} 4)
string(APPEND head "${v}")

# ---- suffix ------------------------------------------------------------------------------------
palp_le_hex(pid_hex ${PID} 2)
palp_le_hex(vid_hex ${VID} 2)
string(HEX "UFD" ufd)
set(suffix "ffff${pid_hex}${vid_hex}1a01${ufd}10")
set(crc 4294967295)
palp_crc32_update_hex(crc "${head}")
palp_crc32_update_file(crc "${BIN}" 0 ${image_size})
palp_crc32_update_hex(crc "${suffix}")
palp_le_hex(crc_hex ${crc} 4)
string(APPEND suffix "${crc_hex}")

# ---- the file ----------------------------------------------------------------------------------
palp_write_hex_bytes("${head}" "${DFU}.head" ${OBJCOPY})
palp_write_hex_bytes("${suffix}" "${DFU}.suffix" ${OBJCOPY})
execute_process(COMMAND ${CMAKE_COMMAND} -E cat "${DFU}.head" "${BIN}" "${DFU}.suffix"
                OUTPUT_FILE "${DFU}" RESULT_VARIABLE rc ERROR_VARIABLE err)
file(REMOVE "${DFU}.head" "${DFU}.suffix")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "writing ${DFU} failed: ${err}")
endif()
file(SIZE "${DFU}" written)
if(NOT written EQUAL file_size)
  message(FATAL_ERROR "${DFU}: ${written} bytes written, expected ${file_size}")
endif()
get_filename_component(name "${DFU}" NAME)
palp_hex32(crc_text ${crc})
message(STATUS "${name}: ${file_size} bytes, one element of ${image_size} bytes at ${ADDRESS}, "
               "suffix ${VID}:${PID} bcdDFU 0x011A dwCRC ${crc_text}")
