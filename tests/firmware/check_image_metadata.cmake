# SPDX-License-Identifier: Apache-2.0
# `palp-proto image` on a built firmware image: the exact text for its .elf, .bin (and .dfu), the
# expected values found independently of palp-proto (size: the .bin's length; CRC: computed here
# by firmware/cmake/image_bytes.cmake; protocol: `palp-proto version`; firmware version: the
# core's DeviceIdentity defaults; git hash: the bytes at 0x420), and the exact error for a
# flipped byte (CRC mismatch naming both values), a truncated copy and a file that is no image.
#   cmake -DPALP_PROTO=<palp-proto> -DIMAGE=<dir/name> (without suffix) -DBOARD=<name (id)>
#         -DLOAD_ADDRESS=0x........ [-DDFU=ON] -DCORE_HEADER=<controller.hpp> -DOBJCOPY=<objcopy>
#         -DWORK_DIR=<dir> -DHINT=<how to build> -P check_image_metadata.cmake
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/image_edit.cmake)

set(bin "${IMAGE}.bin")
set(files "${IMAGE}.elf" "${bin}")
if(DFU)
  list(APPEND files "${IMAGE}.dfu")
endif()
foreach(f IN LISTS files)
  if(NOT EXISTS "${f}")
    message(FATAL_ERROR "${f} does not exist: ${HINT}")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(failures "")

# ---- the expected values -----------------------------------------------------------------------
execute_process(COMMAND ${PALP_PROTO} version OUTPUT_VARIABLE v)
if(NOT v MATCHES "palp protocol ([0-9]+\\.[0-9]+), schema hash (0x[0-9a-f]+)")
  message(FATAL_ERROR "palp-proto version printed '${v}'")
endif()
set(protocol ${CMAKE_MATCH_1})
set(schema ${CMAKE_MATCH_2})
file(READ "${CORE_HEADER}" core)
if(NOT core MATCHES "fw_major = ([0-9]+), fw_minor = ([0-9]+), fw_patch = ([0-9]+)")
  message(FATAL_ERROR "${CORE_HEADER}: no DeviceIdentity fw_major/fw_minor/fw_patch defaults")
endif()
set(version "${CMAKE_MATCH_1}.${CMAKE_MATCH_2}.${CMAKE_MATCH_3}")
file(READ "${bin}" git_hex OFFSET 1056 LIMIT 16 HEX)  # git_hash: 0x400 + 32
string(REGEX REPLACE "(00)+$" "" git_hex "${git_hex}")
string(REGEX MATCHALL ".." chars "${git_hex}")
set(git "")
foreach(c IN LISTS chars)
  math(EXPR c "0x${c}")
  string(ASCII ${c} ch)
  string(APPEND git "${ch}")
endforeach()
file(SIZE "${bin}" size)
set(crc 4294967295)
palp_crc32_update_file(crc "${bin}" 0 1052)  # up to image_crc32 (0x41c)
palp_crc32_update_hex(crc "00000000")
math(EXPR rest "${size} - 1056")
palp_crc32_update_file(crc "${bin}" 1056 ${rest})
palp_crc32_final(crc_text ${crc})

set(metadata "board: ${BOARD}
firmware_version: ${version}
protocol_version: ${protocol}
schema_hash: ${schema}
git_hash: ${git}
image_size: ${size} bytes
image_crc32: ${crc_text}
metadata_layout: 1 at offset 0x400
")

# expect(<file> <exit code> <stdout> <stderr>)
function(expect file code out err)
  execute_process(COMMAND ${PALP_PROTO} image "${file}" RESULT_VARIABLE rc OUTPUT_VARIABLE o
                  ERROR_VARIABLE e)
  message(STATUS "palp-proto image ${file}: exit ${rc}\n${o}${e}")
  if(NOT rc EQUAL code OR NOT o STREQUAL out OR NOT e STREQUAL err)
    set(failures ${failures} "palp-proto image ${file}: exit ${rc} (expected ${code})\n--- stdout\n${o}--- expected\n${out}--- stderr\n${e}--- expected\n${err}"
        PARENT_SCOPE)
  endif()
endfunction()

set(check "check: image_size and image_crc32 match the image\n")
expect("${IMAGE}.elf" 0 "file: ${IMAGE}.elf (ELF, load address ${LOAD_ADDRESS}, ${size} bytes of image)\n${metadata}${check}" "")
expect("${bin}" 0 "file: ${bin} (bin, ${size} bytes of image)\n${metadata}${check}" "")
if(DFU)
  expect("${IMAGE}.dfu" 0 "file: ${IMAGE}.dfu (DfuSe, load address ${LOAD_ADDRESS}, ${size} bytes of image)\n${metadata}${check}" "")
endif()

# ---- damaged copies ------------------------------------------------------------------------------
set(flipped "${WORK_DIR}/flipped.bin")
palp_test_flip_byte("${bin}" "${flipped}" 1280 ${OBJCOPY})
set(c 4294967295)
palp_crc32_update_file(c "${flipped}" 0 1052)
palp_crc32_update_hex(c "00000000")
palp_crc32_update_file(c "${flipped}" 1056 ${rest})
palp_crc32_final(bad_crc_text ${c})
expect("${flipped}" 1 "file: ${flipped} (bin, ${size} bytes of image)\n${metadata}"
       "palp-proto image: ${flipped}: CRC mismatch: the metadata says ${crc_text}, the image's bytes give ${bad_crc_text}: the image is corrupt\n")

set(truncated "${WORK_DIR}/truncated.bin")
palp_test_truncate("${bin}" "${truncated}" 1280 ${OBJCOPY})
expect("${truncated}" 1 "file: ${truncated} (bin, 1280 bytes of image)\n${metadata}"
       "palp-proto image: ${truncated}: size mismatch: the metadata says ${size} bytes, the image has 1280: it is truncated or has bytes added\n")

set(text "${CMAKE_CURRENT_LIST_FILE}")
file(SIZE "${text}" text_size)
expect("${text}" 1 "file: ${text} (bin, ${text_size} bytes of image)\n"
       "palp-proto image: ${text}: not a palp firmware image: no \"palp-img\" metadata block at offset 0x00000400\n")

if(failures)
  list(JOIN failures "\n" all)
  message(FATAL_ERROR "${all}")
endif()
