# SPDX-License-Identifier: Apache-2.0
# Bounds the stack an interrupt handler can use, from GCC's call-graph files, and fails past LIMIT
# or wherever the bound cannot be known.
#
#   cmake -DCI_DIRS=<dir>[,<dir>...] -DROOT=<symbol> -DLIMIT=<bytes> [-DIMAGE=<a.elf>]
#         [-DINDIRECT=<caller>-><target>[|<caller>-><target>...]] [-DCXXFILT=<c++filt>]
#         [-DOBJDUMP=<arm-none-eabi-objdump>] [-DNM=<arm-none-eabi-nm>] -P check_isr_stack.cmake
#   cmake -DSETTINGS=<image>.isr_stack.cmake [-D<setting>=...] [-DHINT=<text>]
#         -P check_isr_stack.cmake
# SETTINGS: the file firmware/CMakeLists.txt (palp_isr_stack_check) writes for an image, which
# sets each of the above unless given on the command line (e.g. -DLIMIT=500 to see it fail);
# the build runs it after the link and ctest again. HINT: how to build what is missing.
#
# The graph: the .ci files below CI_DIRS (the object directories of the image's targets), written
# by `-fcallgraph-info=su` and read by callgraph.cmake (which says what they hold, and the
# INDIRECT format); tail calls stay as edges, which over-counts.
#
# The walk starts at ROOT (the vector entry: its symbol or demangled name, e.g. palp_irq_timer0)
# and takes, for each function, its frame plus the deepest of its callees. A function without a
# frame in the .ci files (libgcc, libc, libm, assembly) is read from IMAGE's machine code
# (library_node below). With IMAGE, ROOT must be in the image and be the function the image's
# symbol ROOT is (what the vector table runs). It fails, naming the function and the call path
# to it, when it meets
#   - a function without a frame and no IMAGE, or library code with an indirect branch or SP set
#     from a register;
#   - a frame GCC calls "dynamic" (alloca, variable-length arrays); "dynamic,bounded" counts as
#     its stated upper bound;
#   - recursion (a function reached again while it is on the path);
#   - an indirect call not resolved by INDIRECT.
# To the deepest path it adds the exception entry frame: on a Cortex-M4F the processor pushes
# the extended frame when the interrupted code had the FPU context active (CONTROL.FPCA = 1):
# R0-R3, R12, LR, PC, xPSR, S0-S15, FPSCR and a reserved word, 26 words = 104 B, plus 4 B when
# it realigns SP to 8 bytes (CCR.STKALIGN) — ARMv7-M Architecture Reference Manual (DDI 0403E),
# B1.5.7 "Stack alignment on exception entry" and B1.5.6 "Exception entry behavior": 108 B.
# Not seen: interrupts that preempt ROOT (each adds its own bound), the stack of the code ROOT
# interrupts, and linker veneers (branches that do not touch SP).
cmake_minimum_required(VERSION 3.25)

set(exception_entry_frame 108)

if(NOT DEFINED HINT)
  set(HINT "")
endif()
if(DEFINED SETTINGS)
  if(NOT EXISTS "${SETTINGS}")
    message(FATAL_ERROR "check_isr_stack: ${SETTINGS} does not exist: ${HINT}")
  endif()
  include("${SETTINGS}")
endif()

foreach(arg CI_DIRS ROOT LIMIT)
  if(NOT DEFINED ${arg} OR "${${arg}}" STREQUAL "")
    message(FATAL_ERROR "check_isr_stack: -D${arg}=... is required")
  endif()
endforeach()
if(NOT LIMIT MATCHES "^[0-9]+$")
  message(FATAL_ERROR "check_isr_stack: -DLIMIT=<bytes> must be a number (got '${LIMIT}')")
endif()
if(DEFINED IMAGE AND NOT IMAGE STREQUAL "")
  if(NOT EXISTS "${IMAGE}")
    message(FATAL_ERROR "check_isr_stack: image ${IMAGE} does not exist: ${HINT}")
  endif()
  if(NOT DEFINED OBJDUMP OR OBJDUMP STREQUAL "")
    find_program(OBJDUMP arm-none-eabi-objdump)
  endif()
  if(NOT OBJDUMP)
    message(FATAL_ERROR "arm-none-eabi-objdump not found: run scripts/install-deps "
                        "(package gcc-arm-none-eabi, which brings binutils-arm-none-eabi)")
  endif()
endif()

include(${CMAKE_CURRENT_LIST_DIR}/callgraph.cmake)

# ---- functions without a .ci node: library code, read from the image -------------------------
# library_node(<symbol>): for a function GCC did not compile here (libgcc, libc, libm), sets the
# global properties frame_<symbol> and calls_<symbol> from its machine code in IMAGE. The frame
# is the sum of every push, vpush, `sub sp, #n` and `str rx, [sp, #-n]!` in the function (an
# upper bound: each path runs a subset); its calls are its bl/blx and its branches to other
# symbols (tail calls). An indirect branch or an SP set from a register cannot be bounded. A
# symbol not in the image is never called (GCC recorded a call it later optimised away): 0 B.
function(library_node symbol path)
  if(NOT DEFINED IMAGE OR IMAGE STREQUAL "")
    cannot_bound("${path}" "${symbol} has no frame in the .ci files and no -DIMAGE to read its "
                           "machine code from")
  endif()
  execute_process(COMMAND "${OBJDUMP}" -d --no-show-raw-insn "--disassemble=${symbol}" "${IMAGE}"
                  OUTPUT_VARIABLE listing RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${OBJDUMP} --disassemble=${symbol} ${IMAGE} failed (${rc})")
  endif()
  set(frame 0)
  set(calls "")
  set(note "not in the image")
  string(REPLACE ";" "," listing "${listing}")
  string(REPLACE "\n" ";" lines "${listing}")
  foreach(line IN LISTS lines)
    if(line MATCHES "^[0-9a-f]+ <${symbol}>:$")
      set(note "machine code")
    endif()
    if(NOT line MATCHES "^ +[0-9a-f]+:\t([a-z0-9.]+)\t?(.*)$")
      continue()
    endif()
    set(op "${CMAKE_MATCH_1}")
    set(args "${CMAKE_MATCH_2}")
    string(REGEX REPLACE "[ \t]*@.*$" "" args "${args}")  # objdump's comments
    if(op MATCHES "^(push|stmdb|vpush|vstmdb)(\\.w)?$" AND
       (op MATCHES "push" OR args MATCHES "^sp!"))
      string(REGEX REPLACE "^.*{(.*)}$" "\\1" registers "${args}")
      string(REPLACE "," ";" registers "${registers}")
      foreach(r IN LISTS registers)
        string(STRIP "${r}" r)
        set(size 4)
        if(r MATCHES "^d")
          set(size 8)
        endif()
        if(r MATCHES "^[a-z]+([0-9]+)-[a-z]+([0-9]+)$")
          math(EXPR frame "${frame} + (${CMAKE_MATCH_2} - ${CMAKE_MATCH_1} + 1) * ${size}")
        else()
          math(EXPR frame "${frame} + ${size}")
        endif()
      endforeach()
    elseif(op MATCHES "^subw?(\\.w)?$" AND args MATCHES "^sp, (sp, )?#([0-9]+)$")
      math(EXPR frame "${frame} + ${CMAKE_MATCH_2}")
    elseif(op MATCHES "^str" AND args MATCHES "\\[sp, #-([0-9]+)\\]!$")
      math(EXPR frame "${frame} + ${CMAKE_MATCH_1}")
    elseif(args MATCHES "^sp," AND NOT op MATCHES "^(add|addw|add\\.w|ldr|ldrd|ldm|ldmia)")
      cannot_bound("${path}" "${symbol} sets SP from a register (${op} ${args})")
    elseif(op MATCHES "^b" AND args MATCHES "^[0-9a-f]+ <([^+>]+)")
      if(NOT CMAKE_MATCH_1 STREQUAL symbol)
        list(APPEND calls "${CMAKE_MATCH_1}")
      endif()
    elseif((op MATCHES "^(blx|bx|mov)" AND args MATCHES "^(pc, )?r[0-9]+$|^ip$|^(pc, )?ip$") OR
           (op MATCHES "^ldr" AND args MATCHES "^pc, " AND NOT args MATCHES "^pc, \\[sp\\], #"))
      cannot_bound("${path}" "${symbol} makes an indirect call (${op} ${args})")
    endif()
  endforeach()
  if(calls)
    list(REMOVE_DUPLICATES calls)
  endif()
  set_property(GLOBAL PROPERTY "frame_${symbol}" ${frame})
  set_property(GLOBAL PROPERTY "calls_${symbol}" "${calls}")
  set_property(GLOBAL PROPERTY "display_${symbol}" "${symbol} [${note}]")
endfunction()

# ---- the walk ------------------------------------------------------------------------------------
# A function's frame, calls and name: from the .ci files, else from library_node.
function(node title path)
  get_property(known GLOBAL PROPERTY "frame_${title}" SET)
  if(NOT known)
    if(DEFINED "frame_${title}")
      set_property(GLOBAL PROPERTY "frame_${title}" ${frame_${title}})
      set_property(GLOBAL PROPERTY "calls_${title}" "${calls_${title}}")
      set_property(GLOBAL PROPERTY "display_${title}" "${display_${title}}")
    else()
      library_node("${title}" "${path}")
    endif()
  endif()
endfunction()

function(describe_path out path)
  set(text "")
  foreach(title IN LISTS path)
    get_property(frame GLOBAL PROPERTY "frame_${title}")
    get_property(name GLOBAL PROPERTY "display_${title}")
    if("${name}" STREQUAL "")
      set(name "${display_${title}}")
    endif()
    if("${frame}" STREQUAL "" AND DEFINED "frame_${title}")
      set(frame "${frame_${title}}")
    elseif("${frame}" STREQUAL "")
      set(frame "?")
    endif()
    string(APPEND text "\n    ${name} (${frame} B)")
  endforeach()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

function(cannot_bound path)
  list(JOIN ARGN "" why)
  describe_path(text "${path}")
  message(FATAL_ERROR "check_isr_stack: cannot bound the stack of ${ROOT}: ${why}\n"
                      "  call path from ${ROOT} (frames):${text}")
endfunction()

# worst(<title> <path>): sets the global properties bound_<title> (bytes, its frame included) and
# deepest_<title> (the deepest path from it), or fails.
function(worst title path)
  get_property(done GLOBAL PROPERTY "bound_${title}" SET)
  if(done)
    return()
  endif()
  list(APPEND path "${title}")
  if(DEFINED "dynamic_${title}")
    cannot_bound("${path}" "${display_${title}} has a dynamic frame (alloca or a "
                           "variable-length array)")
  endif()
  node("${title}" "${path}")
  get_property(frame GLOBAL PROPERTY "frame_${title}")
  get_property(callees GLOBAL PROPERTY "calls_${title}")
  set_property(GLOBAL PROPERTY "on_path_${title}" TRUE)
  if(DEFINED "indirect_at_${title}")
    if(NOT DEFINED "allowed_from_${title}")
      list(JOIN "indirect_at_${title}" ", " where)
      cannot_bound("${path}" "${display_${title}} makes an indirect call (at ${where}) that "
                             "INDIRECT does not resolve: list its targets as <caller>-><target>")
    endif()
    list(APPEND callees ${allowed_from_${title}})
    list(REMOVE_DUPLICATES callees)
  endif()
  set(deepest_bytes 0)
  set(deepest_path "")
  foreach(callee IN LISTS callees)
    get_property(cycle GLOBAL PROPERTY "on_path_${callee}")
    if(cycle)
      list(APPEND path "${callee}")
      cannot_bound("${path}" "recursion: ${display_${callee}} is reached again on this path")
    endif()
    worst("${callee}" "${path}")
    get_property(bytes GLOBAL PROPERTY "bound_${callee}")
    if(bytes GREATER deepest_bytes OR deepest_path STREQUAL "")
      set(deepest_bytes ${bytes})
      get_property(deepest_path GLOBAL PROPERTY "deepest_${callee}")
    endif()
  endforeach()
  set_property(GLOBAL PROPERTY "on_path_${title}" FALSE)
  math(EXPR bound "${frame} + ${deepest_bytes}")
  set_property(GLOBAL PROPERTY "bound_${title}" ${bound})
  set_property(GLOBAL PROPERTY "deepest_${title}" "${title};${deepest_path}")
endfunction()

resolve_function(root "${ROOT}")
# The root must be what runs: in the image, and the function the image's symbol ROOT (the vector
# table's name) is, not a weak default beside a C++-mangled handler of the same plain name.
if(DEFINED IMAGE AND NOT IMAGE STREQUAL "")
  if(NOT DEFINED NM OR NM STREQUAL "")
    find_program(NM arm-none-eabi-nm)
  endif()
  execute_process(COMMAND "${NM}" "${IMAGE}" OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${NM} ${IMAGE} failed (${rc})")
  endif()
  set(root_symbol "${symbol_${root}}")
  if(NOT symbols MATCHES "(^|\n)([0-9a-f]+) [TtWw] ${root_symbol}\n")
    message(FATAL_ERROR "check_isr_stack: ${display_${root}} (${root_symbol}) is not in ${IMAGE}: "
                        "nothing references it (a handler the vector table names must be "
                        "extern \"C\")")
  endif()
  set(root_address ${CMAKE_MATCH_2})
  if(symbols MATCHES "(^|\n)([0-9a-f]+) [TtWw] ${ROOT}\n" AND
     NOT CMAKE_MATCH_2 STREQUAL root_address)
    message(FATAL_ERROR "check_isr_stack: the image's ${ROOT} is at 0x${CMAKE_MATCH_2}, not "
                        "${display_${root}} (${root_symbol}, 0x${root_address}): the vector "
                        "runs another function, e.g. the weak default (declare the handler "
                        "extern \"C\")")
  endif()
endif()
worst("${root}" "")
get_property(bound GLOBAL PROPERTY "bound_${root}")
get_property(deepest GLOBAL PROPERTY "deepest_${root}")
list(REMOVE_ITEM deepest "")
describe_path(path_text "${deepest}")
math(EXPR total "${bound} + ${exception_entry_frame}")
string(CONCAT report "stack of ${ROOT}: ${total} B (limit ${LIMIT} B) = ${bound} B of frames on "
       "the deepest path + ${exception_entry_frame} B exception entry (extended FPU frame, "
       "aligned); deepest path:${path_text}")
if(total GREATER LIMIT)
  message(FATAL_ERROR "check_isr_stack: ${ROOT} is over its limit: ${report}")
endif()
message(STATUS "${report}")
