# SPDX-License-Identifier: Apache-2.0
# The call graph of an image's code from GCC's -fcallgraph-info=su files, for cmake -P scripts
# (check_isr_stack.cmake, ccm_sections.cmake) to include after setting CI_DIRS (comma-separated
# object directories, searched for .ci files), optionally INDIRECT and CXXFILT.
#
# The .ci files (VCG format, one per object): one node per function compiled, labelled with its
# frame ("24 bytes (static)"), one edge per call GCC emitted (inlined calls are gone), the target
# `__indirect_call` for a call through a pointer, and nodes without a frame for functions
# compiled elsewhere. Titles are the symbols; a function with internal linkage is
# "<file>:<symbol>". A symbol compiled in several objects (inline functions, weak defaults)
# takes the largest frame and all the calls.
#
# Defines, for each function title T: seen_T; frame_T (bytes; absent: no frame here, i.e.
# library code); dynamic_T (its frame is "dynamic"); calls_T (titles it calls);
# indirect_at_T (where it calls through a pointer); allowed_from_T (what INDIRECT lets those
# calls reach); display_T (the demangled name); symbol_T (the symbol without "<file>:"); and
# `titles` (every title).
#
# INDIRECT: "<caller>-><target>[|<caller>-><target>...]": the indirect calls made in <caller>
# (the function holding the call after inlining) may reach <target>; both are demangled names
# without parameters, e.g.
# `palp::qemu::QemuBoard::on_tick_irq->palp::app::App<palp::qemu::QemuBoard>::tick_entry`. An
# entry naming no function in the graph is an error (a stale list).
if(NOT DEFINED CXXFILT OR CXXFILT STREQUAL "")
  find_program(CXXFILT NAMES arm-none-eabi-c++filt c++filt)
endif()
if(NOT CXXFILT)
  message(FATAL_ERROR "arm-none-eabi-c++filt not found: run scripts/install-deps "
                      "(package gcc-arm-none-eabi, which brings binutils-arm-none-eabi)")
endif()

# ---- read the graph ------------------------------------------------------------------------------
string(REPLACE "," ";" CI_DIRS "${CI_DIRS}")
set(ci_files "")
foreach(dir IN LISTS CI_DIRS)
  if(NOT IS_DIRECTORY "${dir}")
    message(FATAL_ERROR "callgraph: object directory ${dir} does not exist")
  endif()
  file(GLOB_RECURSE found "${dir}/*.ci")
  list(APPEND ci_files ${found})
endforeach()
if(ci_files STREQUAL "")
  message(FATAL_ERROR "callgraph: no .ci file below ${CI_DIRS} (compiled without "
                      "-fcallgraph-info=su?)")
endif()

set(titles "")  # every function seen, defined or not
foreach(ci IN LISTS ci_files)
  file(STRINGS "${ci}" lines REGEX "^(node|edge): ")
  foreach(line IN LISTS lines)
    if(line MATCHES "^node: { title: \"([^\"]+)\" label: \"([^\"]*)\"")
      set(title "${CMAKE_MATCH_1}")
      set(label "${CMAKE_MATCH_2}")
      if(NOT DEFINED "seen_${title}")
        set("seen_${title}" TRUE)
        list(APPEND titles "${title}")
      endif()
      if(label MATCHES "\\\\n([0-9]+) bytes \\(([a-z,]+)\\)$")
        set(bytes ${CMAKE_MATCH_1})
        set(kind ${CMAKE_MATCH_2})
        if(kind STREQUAL "dynamic")
          set("dynamic_${title}" TRUE)
        endif()
        if(NOT DEFINED "frame_${title}" OR bytes GREATER "${frame_${title}}")
          set("frame_${title}" ${bytes})
        endif()
        string(REGEX REPLACE "\\\\n.*" "" "signature_${title}" "${label}")
      endif()
    elseif(line MATCHES
           "^edge: { sourcename: \"([^\"]+)\" targetname: \"([^\"]+)\"( label: \"([^\"]*)\")?")
      set(source "${CMAKE_MATCH_1}")
      set(target "${CMAKE_MATCH_2}")
      if(target STREQUAL "__indirect_call")
        if(CMAKE_MATCH_4)
          list(APPEND "indirect_at_${source}" "${CMAKE_MATCH_4}")
        else()
          list(APPEND "indirect_at_${source}" "?")
        endif()
      else()
        list(APPEND "calls_${source}" "${target}")
      endif()
    endif()
  endforeach()
endforeach()
foreach(title IN LISTS titles)
  if(DEFINED "calls_${title}")
    list(REMOVE_DUPLICATES "calls_${title}")
  endif()
endforeach()

# Demangled names without parameters ("palp::fw::Controller::tick"), for INDIRECT and messages.
string(REGEX REPLACE "(^|;)[^;]*:" "\\1" symbols "${titles}")  # drop "<file>:" of local titles
execute_process(COMMAND "${CXXFILT}" ${symbols} OUTPUT_VARIABLE demangled RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${CXXFILT} failed (${rc})")
endif()
string(REGEX REPLACE "\n$" "" demangled "${demangled}")
string(REPLACE "\n" ";" demangled "${demangled}")
list(LENGTH titles n_titles)
list(LENGTH demangled n_demangled)
if(NOT n_titles EQUAL n_demangled)
  message(FATAL_ERROR "callgraph: ${CXXFILT} returned ${n_demangled} names for ${n_titles}")
endif()
math(EXPR last "${n_titles} - 1")
foreach(k RANGE ${last})
  list(GET titles ${k} title)
  list(GET demangled ${k} name)
  set("display_${title}" "${name}")
  string(REGEX REPLACE "^.*:" "" "symbol_${title}" "${title}")
  string(REGEX REPLACE "\\(.*$" "" base "${name}")  # parameters and " [clone .isra.0]" go
  list(APPEND "titles_named_${base}" "${title}")
endforeach()

# ---- INDIRECT: the allowed targets of each caller's indirect calls ---------------------------
set(allowed_callers "")
if(DEFINED INDIRECT AND NOT INDIRECT STREQUAL "")
  string(REPLACE "|" ";" entries "${INDIRECT}")
  foreach(entry IN LISTS entries)
    if(NOT entry MATCHES "^(.+)->(.+)$")
      message(FATAL_ERROR "callgraph: INDIRECT entry '${entry}' is not <caller>-><target>")
    endif()
    set(caller "${CMAKE_MATCH_1}")
    set(target "${CMAKE_MATCH_2}")
    foreach(name IN ITEMS "${caller}" "${target}")
      if(NOT DEFINED "titles_named_${name}")
        message(FATAL_ERROR "callgraph: INDIRECT entry '${entry}': no function '${name}' in "
                            "the call graph (renamed, or the list is stale)")
      endif()
    endforeach()
    foreach(caller_title IN LISTS "titles_named_${caller}")
      list(APPEND "allowed_from_${caller_title}" ${titles_named_${target}})
    endforeach()
  endforeach()
endif()

# resolve_function(<out> <name>): the title of the one function whose title or demangled name
# without parameters is <name> (e.g. palp_irq_timer0, ADC1_2_IRQHandler); fails otherwise.
function(resolve_function out name)
  if(DEFINED "seen_${name}")
    set(${out} "${name}" PARENT_SCOPE)
    return()
  endif()
  set(found ${titles_named_${name}})
  list(LENGTH found n)
  if(n EQUAL 0)
    message(FATAL_ERROR "callgraph: no function '${name}' in the .ci files below ${CI_DIRS}")
  elseif(n GREATER 1)
    message(FATAL_ERROR "callgraph: '${name}' names ${n} functions (${found}): give the symbol")
  endif()
  set(${out} "${found}" PARENT_SCOPE)
endfunction()
