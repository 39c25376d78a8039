# SPDX-License-Identifier: Apache-2.0
# Binary helpers for the post-build scripts (fill_metadata.cmake, make_dfu.cmake), in plain CMake
# so the build needs nothing but CMake and the cross toolchain.
#
# Bytes are handled as lower-case hex text ("0a1b..."), as file(READ ... HEX) gives them: a CMake
# string cannot hold a NUL byte, so no script writes binary with file(WRITE). Bytes are written
# by palp_write_hex_bytes: as Intel HEX text, which the toolchain's objcopy turns into binary
# (`objcopy -I ihex -O binary`); files are joined with `cmake -E cat` (binary-safe).
#
# palp_crc32_*: CRC-32/ISO-HDLC, the protocol's CRC (protocol/include/palp/protocol/crc32.hpp):
# reflected polynomial 0xEDB88320, state starts at 0xFFFFFFFF; palp_crc32_final XORs 0xFFFFFFFF.
# A DFU suffix's dwCRC is the state without that XOR (usb-dfu-facts.md §6.1). Cost: two math()
# calls a byte, read in 4 KB chunks so no command copies a whole image; fill_metadata.cmake takes
# 0.4 s on the 74 KB QEMU image.

# Table T[n] of the byte-wise CRC, as variables PALP_CRC_T0 ... PALP_CRC_T255 (a variable look-up
# per byte; list(GET) would re-parse a 256-entry list every byte), made once, when this file is
# included (in the including scope, so every function called from there sees it).
foreach(_palp_n RANGE 255)
  set(_palp_c ${_palp_n})
  foreach(_palp_k RANGE 7)
    math(EXPR _palp_low "${_palp_c} & 1")
    if(_palp_low)
      math(EXPR _palp_c "(${_palp_c} >> 1) ^ 0xEDB88320")
    else()
      math(EXPR _palp_c "${_palp_c} >> 1")
    endif()
  endforeach()
  set(PALP_CRC_T${_palp_n} ${_palp_c})
endforeach()
unset(_palp_n)
unset(_palp_c)
unset(_palp_k)
unset(_palp_low)

# palp_crc32_update_hex(<state-var> <hex>): feeds the bytes of <hex> into the CRC state.
function(palp_crc32_update_hex state_var hex)
  set(crc ${${state_var}})
  string(REGEX MATCHALL "[0-9a-fA-F][0-9a-fA-F]" bytes "${hex}")
  foreach(b IN LISTS bytes)
    math(EXPR i "(${crc} ^ 0x${b}) & 255")
    math(EXPR crc "${PALP_CRC_T${i}} ^ (${crc} >> 8)")
  endforeach()
  set(${state_var} ${crc} PARENT_SCOPE)
endfunction()

# palp_crc32_update_file(<state-var> <file> <offset> <length>): the file's bytes [offset,
# offset + length), read 4 KB at a time.
function(palp_crc32_update_file state_var file offset length)
  set(crc ${${state_var}})
  set(at ${offset})
  math(EXPR end "${offset} + ${length}")
  while(at LESS end)
    math(EXPR n "${end} - ${at}")
    if(n GREATER 4096)
      set(n 4096)
    endif()
    file(READ "${file}" chunk OFFSET ${at} LIMIT ${n} HEX)
    palp_crc32_update_hex(crc "${chunk}")
    math(EXPR at "${at} + ${n}")
  endwhile()
  set(${state_var} ${crc} PARENT_SCOPE)
endfunction()

# palp_crc32_final(<out-var> <state>): the CRC as "0x%08x" text (what palp-proto prints).
function(palp_crc32_final out_var state)
  math(EXPR v "${state} ^ 0xFFFFFFFF")
  palp_hex32(v ${v})
  set(${out_var} ${v} PARENT_SCOPE)
endfunction()

# palp_hex32(<out-var> <value>): "0x%08x".
function(palp_hex32 out_var value)
  palp_le_hex(le ${value} 4)
  string(REGEX REPLACE "^(..)(..)(..)(..)$" "0x\\4\\3\\2\\1" v "${le}")
  set(${out_var} ${v} PARENT_SCOPE)
endfunction()

# palp_le_hex(<out-var> <value> <bytes>): <value> as <bytes> little-endian bytes in hex text.
function(palp_le_hex out_var value nbytes)
  set(hex "")
  math(EXPR last "${nbytes} - 1")
  foreach(k RANGE ${last})
    math(EXPR b "(${value} >> (8 * ${k})) & 255" OUTPUT_FORMAT HEXADECIMAL)
    string(SUBSTRING "${b}" 2 -1 b)
    string(LENGTH "${b}" len)
    if(len EQUAL 1)
      set(b "0${b}")
    endif()
    string(APPEND hex "${b}")
  endforeach()
  string(TOLOWER "${hex}" hex)
  set(${out_var} ${hex} PARENT_SCOPE)
endfunction()

# palp_hex_u32_le(<out-var> <hex> <byte-offset>): the little-endian u32 at <byte-offset> of <hex>.
function(palp_hex_u32_le out_var hex offset)
  math(EXPR at "2 * ${offset}")
  string(SUBSTRING "${hex}" ${at} 8 w)
  string(REGEX REPLACE "^(..)(..)(..)(..)$" "\\4\\3\\2\\1" be "${w}")
  math(EXPR v "0x${be}")
  set(${out_var} ${v} PARENT_SCOPE)
endfunction()

# palp_write_hex_bytes(<hex> <file> <objcopy>): writes the bytes of <hex> (at most 64 KB) to
# <file>, through an Intel HEX file <file>.ihex: 32-byte data records, then the end record.
function(palp_write_hex_bytes hex file objcopy)
  string(LENGTH "${hex}" chars)
  math(EXPR size "${chars} / 2")
  if(size GREATER 65536 OR size EQUAL 0)
    message(FATAL_ERROR "palp_write_hex_bytes: ${size} bytes (1 to 65536 only)")
  endif()
  set(text "")
  set(at 0)
  while(at LESS size)
    math(EXPR n "${size} - ${at}")
    if(n GREATER 32)
      set(n 32)
    endif()
    math(EXPR from "2 * ${at}")
    math(EXPR len "2 * ${n}")
    string(SUBSTRING "${hex}" ${from} ${len} data)
    palp_le_hex(count ${n} 1)
    palp_le_hex(addr_le ${at} 2)
    string(REGEX REPLACE "^(..)(..)$" "\\2\\1" addr "${addr_le}")  # addresses are big-endian
    string(REGEX MATCHALL ".." record_bytes "${count}${addr}00${data}")
    list(JOIN record_bytes "+0x" sum)
    math(EXPR check "(256 - ((0x${sum}) & 255)) & 255")
    palp_le_hex(check ${check} 1)
    string(TOUPPER ":${count}${addr}00${data}${check}\n" line)
    string(APPEND text "${line}")
    math(EXPR at "${at} + ${n}")
  endwhile()
  string(APPEND text ":00000001FF\n")
  file(WRITE "${file}.ihex" "${text}")
  execute_process(COMMAND ${objcopy} -I ihex -O binary "${file}.ihex" "${file}"
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${objcopy} -I ihex -O binary ${file}.ihex failed: ${err}")
  endif()
  file(SIZE "${file}" written)
  if(NOT written EQUAL size)
    message(FATAL_ERROR "${file}: wrote ${written} bytes, expected ${size}")
  endif()
  file(REMOVE "${file}.ihex")
endfunction()
