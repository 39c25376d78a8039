# SPDX-License-Identifier: Apache-2.0
# Post-build: fills image_size and image_crc32 of the image's metadata block (layout 1,
# protocol/include/palp/protocol/image_metadata.hpp) in the .elf, then writes the .bin from it.
#
#   cmake -DELF=<image.elf> -DBIN=<image.bin> -DOBJCOPY=<objcopy> -DOBJDUMP=<objdump>
#         -P fill_metadata.cmake
#
# How: `objdump -h` gives the .palp_metadata section's load address and the image's first
# (the lowest load address of a loaded section: where `objcopy -O binary` starts the .bin), so
# the block's offset in the .bin; `objcopy -O binary` gives the image's bytes and size; the CRC
# (image_bytes.cmake) runs over them with the size field set and the CRC field as zeros. The
# patched 48-byte block goes back into the .elf with `objcopy --update-section` (written as
# Intel HEX and converted by objcopy: CMake strings cannot hold NUL bytes), and the .bin is
# written again from that .elf, so the two always agree. Running it twice gives the same bytes.
# Field offsets below are layout 1's; the script refuses any other layout_version.
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/image_bytes.cmake)

foreach(var ELF BIN OBJCOPY OBJDUMP)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "fill_metadata.cmake: -D${var}=... is required")
  endif()
endforeach()
set(block_size 48)      # kImageMetadataSize
set(layout_at 8)        # layout_version (u16)
set(size_at 24)         # kImageSizeFieldOffset
set(crc_at 28)          # kImageCrcFieldOffset

# ---- where the block is: load addresses from the section headers --------------------------
execute_process(COMMAND ${OBJDUMP} -h "${ELF}" OUTPUT_VARIABLE headers RESULT_VARIABLE rc
                ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${OBJDUMP} -h ${ELF} failed: ${err}")
endif()
# "  1 .palp_metadata 00000030  00000400  00000400  00010400  2**2\n      CONTENTS, ALLOC, LOAD, ..."
set(x "[0-9a-f]+")
string(REGEX MATCHALL " *[0-9]+ [^ ]+ +${x} +${x} +${x} +${x} +2\\*\\*[0-9]+\n[^\n]*" sections "${headers}")
set(base "")
set(meta_lma "")
foreach(s IN LISTS sections)
  string(REGEX MATCH "^ *[0-9]+ ([^ ]+) +(${x}) +${x} +(${x})" _ "${s}")
  set(name ${CMAKE_MATCH_1})
  math(EXPR size "0x${CMAKE_MATCH_2}")
  math(EXPR lma "0x${CMAKE_MATCH_3}")
  if(NOT s MATCHES "LOAD" OR size EQUAL 0)
    continue()
  endif()
  if(base STREQUAL "" OR lma LESS base)
    set(base ${lma})
  endif()
  if(name STREQUAL ".palp_metadata")
    set(meta_lma ${lma})
    set(meta_size ${size})
  endif()
endforeach()
if(meta_lma STREQUAL "")
  message(FATAL_ERROR "${ELF} has no .palp_metadata section: build the image with "
                      "palp_image_metadata() (firmware/CMakeLists.txt)")
endif()
if(NOT meta_size EQUAL block_size)
  message(FATAL_ERROR "${ELF}: .palp_metadata is ${meta_size} bytes, layout 1 has ${block_size}")
endif()
math(EXPR offset "${meta_lma} - ${base}")

# ---- the image's bytes as linked, the block, the CRC -----------------------------------------
execute_process(COMMAND ${OBJCOPY} -O binary "${ELF}" "${BIN}" RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${OBJCOPY} -O binary ${ELF} failed: ${err}")
endif()
file(SIZE "${BIN}" image_size)
file(READ "${BIN}" block OFFSET ${offset} LIMIT ${block_size} HEX)
string(SUBSTRING "${block}" 16 4 layout_le)
string(REGEX REPLACE "^(..)(..)$" "\\2\\1" layout_be "${layout_le}")
math(EXPR layout "0x${layout_be}")
if(NOT layout EQUAL 1)
  message(FATAL_ERROR "${ELF}: metadata layout_version ${layout} at image offset ${offset}; "
                      "this script fills layout 1 only")
endif()

palp_le_hex(size_hex ${image_size} 4)
set(crc 4294967295)
math(EXPR head "${offset} + ${size_at}")
palp_crc32_update_file(crc "${BIN}" 0 ${head})
palp_crc32_update_hex(crc "${size_hex}00000000")
math(EXPR tail_at "${offset} + ${crc_at} + 4")
math(EXPR tail "${image_size} - ${tail_at}")
palp_crc32_update_file(crc "${BIN}" ${tail_at} ${tail})
palp_crc32_final(image_crc ${crc})
palp_le_hex(crc_hex ${image_crc} 4)

# ---- into the .elf, then the .bin from it ------------------------------------------------------
math(EXPR keep_chars "2 * ${size_at}")
math(EXPR rest_at "2 * (${crc_at} + 4)")
string(SUBSTRING "${block}" 0 ${keep_chars} before)
string(SUBSTRING "${block}" ${rest_at} -1 after)
set(filled "${before}${size_hex}${crc_hex}${after}")
palp_write_hex_bytes("${filled}" "${BIN}.metadata" ${OBJCOPY})
execute_process(COMMAND ${OBJCOPY} --update-section ".palp_metadata=${BIN}.metadata" "${ELF}"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${OBJCOPY} --update-section .palp_metadata ${ELF} failed: ${err}")
endif()
file(REMOVE "${BIN}.metadata")
execute_process(COMMAND ${OBJCOPY} -O binary "${ELF}" "${BIN}" RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${OBJCOPY} -O binary ${ELF} failed: ${err}")
endif()

# the .bin written from the patched .elf holds the filled block and kept its size
file(SIZE "${BIN}" size_after)
file(READ "${BIN}" block_after OFFSET ${offset} LIMIT ${block_size} HEX)
if(NOT size_after EQUAL image_size OR NOT block_after STREQUAL filled)
  message(FATAL_ERROR "${BIN}: the block read back differs from the one written into ${ELF}")
endif()
get_filename_component(name "${ELF}" NAME_WE)
math(EXPR offset_hex "${offset}" OUTPUT_FORMAT HEXADECIMAL)
message(STATUS "${name}: metadata at ${offset_hex}: image_size ${image_size} bytes, "
               "image_crc32 ${image_crc}")
