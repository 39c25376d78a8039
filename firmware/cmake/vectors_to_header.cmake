# SPDX-License-Identifier: Apache-2.0
# Converts the protocol's golden vectors (protocol/vectors/messages.txt and malformed.txt) into
# a C++ header of const byte arrays for the firmware test image. Runs as a CMake script, so the
# build needs nothing beyond CMake (no python, no xxd):
#
#   cmake -DMESSAGES=<messages.txt> -DMALFORMED=<malformed.txt> -DOUTPUT=<header.hpp>
#         -P vectors_to_header.cmake
#
# Format (protocol/SPEC.md section 11, read the same way as parse_vectors() in
# protocol/host/vectors.cpp): lines starting with '#' and empty lines are skipped; a record
# starts with `vector NAME`; every other line is `keyword value` with keyword one of about,
# expect, header, field, payload, wire. An unknown keyword, a malformed hex line or a record
# without its required lines stops the build with the file and line.
# The header also carries the SHA-256 of both files, which the image prints, so a test can tell
# an image built from other vectors (tests/firmware/run_qemu_image.cmake).
cmake_minimum_required(VERSION 3.25)

foreach(var MESSAGES MALFORMED OUTPUT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "vectors_to_header.cmake: -D${var}=... is required")
  endif()
endforeach()

# CMake lists split on ';' and group on '[' ']', and '\' escapes: hide those characters behind
# control characters while the text is a list of lines, and put them back in c_string().
string(ASCII 1 kSemi)
string(ASCII 2 kOpen)
string(ASCII 3 kClose)
string(ASCII 4 kBackslash)

function(read_lines path out_var)
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "vectors_to_header.cmake: ${path} does not exist "
                        "(generate it with `palp-proto vectors protocol/vectors`)")
  endif()
  file(READ "${path}" text)
  string(REPLACE "\\" "${kBackslash}" text "${text}")
  string(REPLACE ";" "${kSemi}" text "${text}")
  string(REPLACE "[" "${kOpen}" text "${text}")
  string(REPLACE "]" "${kClose}" text "${text}")
  string(REPLACE "\r" "" text "${text}")
  string(REPLACE "\n" ";" text "${text}")
  set(${out_var} "${text}" PARENT_SCOPE)
endfunction()

# A C++ string literal (with quotes) holding text as it was in the file.
function(c_string text out_var)
  string(REPLACE "\"" "\\\"" text "${text}")
  string(REPLACE "${kBackslash}" "\\\\" text "${text}")
  string(REPLACE "${kSemi}" ";" text "${text}")
  string(REPLACE "${kOpen}" "[" text "${text}")
  string(REPLACE "${kClose}" "]" text "${text}")
  set(${out_var} "\"${text}\"" PARENT_SCOPE)
endfunction()

function(fail file line what)
  message(FATAL_ERROR "${file}:${line}: ${what}")
endfunction()

# hex: "01 a2 ff" -> out_var: "0x01, 0xa2, 0xff," (16 per line), count_var: 3.
function(hex_to_c hex file line out_var count_var)
  set(out "")
  set(n 0)
  if(NOT hex STREQUAL "")
    string(REPLACE " " ";" tokens "${hex}")
    foreach(t IN LISTS tokens)
      if(NOT t MATCHES "^[0-9a-fA-F][0-9a-fA-F]$")
        fail("${file}" "${line}" "'${t}' is not a hex byte (expected 'hh hh ...')")
      endif()
      math(EXPR col "${n} % 16")
      if(col EQUAL 0)
        string(APPEND out "\n    ")
      else()
        string(APPEND out " ")
      endif()
      string(APPEND out "0x${t},")
      math(EXPR n "${n} + 1")
    endforeach()
  endif()
  set(${out_var} "${out}" PARENT_SCOPE)
  set(${count_var} ${n} PARENT_SCOPE)
endfunction()

# `header major=0 minor=1 id=0x01 flags=0x00 seq=1 payload_len=22` -> h_major ... h_payload_len
macro(parse_header file line header)
  foreach(hkey major:255 minor:255 id:255 flags:255 seq:65535 payload_len:65535)
    string(REPLACE ":" ";" hkey_max "${hkey}")
    list(GET hkey_max 0 hkey)
    list(GET hkey_max 1 hmax)
    if(NOT "${header}" MATCHES "(^| )${hkey}=(0x[0-9a-fA-F]+|[0-9]+)( |$)")
      fail("${file}" "${line}" "header has no ${hkey}=<number>: '${header}'")
    endif()
    set(h_${hkey} "${CMAKE_MATCH_2}")
    math(EXPR hvalue "${h_${hkey}}")
    if(hvalue GREATER hmax)
      fail("${file}" "${line}" "header ${hkey}=${h_${hkey}} is larger than ${hmax}")
    endif()
  endforeach()
endmacro()

set(arrays "")       # the byte arrays
set(messages "")     # MessageVector initialisers
set(malformed "")    # MalformedVector initialisers
set(message_count 0)
set(malformed_count 0)

# Emits the record in the rec_* variables (a macro: it appends to the variables above).
macro(flush_record file kind)
  if(NOT rec_name STREQUAL "")
    if(NOT rec_has_wire)
      fail("${file}" "${rec_line}" "vector ${rec_name} has no 'wire' line")
    endif()
    hex_to_c("${rec_wire}" "${file}" "${rec_wire_line}" wire_c wire_n)
    if(wire_n EQUAL 0)
      fail("${file}" "${rec_wire_line}" "vector ${rec_name}: 'wire' is empty")
    endif()
    c_string("${rec_name}" name_c)
    if("${kind}" STREQUAL "messages")
      set(index ${message_count})
      if(NOT rec_has_header OR NOT rec_has_payload)
        fail("${file}" "${rec_line}" "vector ${rec_name} needs a 'header' and a 'payload' line")
      endif()
      parse_header("${file}" "${rec_header_line}" "${rec_header}")
      hex_to_c("${rec_payload}" "${file}" "${rec_payload_line}" payload_c payload_n)
      string(APPEND arrays "inline constexpr std::uint8_t m${index}_wire[] = {${wire_c}\n};\n")
      if(payload_n EQUAL 0)
        set(payload_ref "nullptr")
      else()
        string(APPEND arrays
               "inline constexpr std::uint8_t m${index}_payload[] = {${payload_c}\n};\n")
        set(payload_ref "data::m${index}_payload")
      endif()
      string(APPEND messages
             "    {${name_c}, ${rec_line}, ${h_major}, ${h_minor}, ${h_id}, ${h_flags}, ${h_seq}, "
             "${h_payload_len}, ${payload_ref}, ${payload_n}, data::m${index}_wire, ${wire_n}},\n")
      math(EXPR message_count "${message_count} + 1")
    else()
      set(index ${malformed_count})
      if(NOT rec_has_expect)
        fail("${file}" "${rec_line}" "vector ${rec_name} has no 'expect' line")
      endif()
      c_string("${rec_about}" about_c)
      c_string("${rec_expect}" expect_c)
      string(APPEND arrays "inline constexpr std::uint8_t x${index}_wire[] = {${wire_c}\n};\n")
      string(APPEND malformed
             "    {${name_c}, ${rec_line}, ${about_c}, ${expect_c}, data::x${index}_wire, ${wire_n}},\n")
      math(EXPR malformed_count "${malformed_count} + 1")
    endif()
  endif()
  foreach(field name line about expect header payload wire)
    set(rec_${field} "")
  endforeach()
  foreach(field header payload wire expect)
    set(rec_has_${field} FALSE)
  endforeach()
endmacro()

macro(parse_file path kind)
  get_filename_component(file "${path}" NAME)
  read_lines("${path}" lines)
  set(line_no 0)
  set(rec_name "")
  flush_record("${file}" ${kind})
  foreach(line IN LISTS lines)
    math(EXPR line_no "${line_no} + 1")
    if(line STREQUAL "" OR line MATCHES "^#")
      continue()
    endif()
    string(FIND "${line}" " " sp)
    if(sp LESS 1)
      fail("${file}" "${line_no}" "expected '<keyword> <value>'")
    endif()
    string(SUBSTRING "${line}" 0 ${sp} key)
    math(EXPR value_at "${sp} + 1")
    string(SUBSTRING "${line}" ${value_at} -1 value)
    if(key STREQUAL "vector")
      flush_record("${file}" ${kind})
      set(rec_name "${value}")
      set(rec_line ${line_no})
    elseif(rec_name STREQUAL "")
      fail("${file}" "${line_no}" "'${key}' before the first 'vector'")
    elseif(key STREQUAL "about")
      set(rec_about "${value}")
    elseif(key STREQUAL "field")
      # the decoded fields, for people; the test checks the bytes
    elseif(key MATCHES "^(expect|header|payload|wire)$")
      set(rec_${key} "${value}")
      set(rec_${key}_line ${line_no})
      set(rec_has_${key} TRUE)
    else()
      fail("${file}" "${line_no}" "unknown keyword '${key}'")
    endif()
  endforeach()
  flush_record("${file}" ${kind})
endmacro()

parse_file("${MESSAGES}" messages)
parse_file("${MALFORMED}" malformed)

if(message_count EQUAL 0 OR malformed_count EQUAL 0)
  message(FATAL_ERROR "vectors_to_header.cmake: ${MESSAGES} has ${message_count} vectors and "
                      "${MALFORMED} has ${malformed_count}; both need at least one")
endif()

file(SHA256 "${MESSAGES}" messages_sha)
file(SHA256 "${MALFORMED}" malformed_sha)

file(WRITE "${OUTPUT}" "\
// Generated by firmware/cmake/vectors_to_header.cmake from
//   ${MESSAGES}
//   ${MALFORMED}
// Do not edit: the build regenerates it when either file changes.
#pragma once

#include <cstddef>
#include <cstdint>

#include \"golden_vectors.hpp\"

namespace palp::fw::vectors {

inline constexpr char kMessagesSha256[] = \"${messages_sha}\";
inline constexpr char kMalformedSha256[] = \"${malformed_sha}\";

namespace data {
${arrays}}  // namespace data

inline constexpr MessageVector kMessages[] = {
    // name, line, major, minor, id, flags, seq, payload_len, payload, size, wire, size
${messages}};
inline constexpr std::size_t kMessageCount = ${message_count};

inline constexpr MalformedVector kMalformed[] = {
    // name, line, about, expect, wire, size
${malformed}};
inline constexpr std::size_t kMalformedCount = ${malformed_count};

}  // namespace palp::fw::vectors
")
