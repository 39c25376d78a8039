# SPDX-License-Identifier: Apache-2.0
# Fails when a firmware image contains heap or C++ exception machinery: the firmware has no heap
# and no exceptions (DESIGN.md, "Firmware principles"), so any of these symbols means something
# pulled in malloc or the unwinder.
#
#   cmake [-DNM=<arm-none-eabi-nm>] -DIMAGE=<image.elf> -P check_image_symbols.cmake
#   cmake [-DNM=<arm-none-eabi-nm>] -DIMAGE_DIR=<dir> [-DREQUIRED=<a.elf,b.elf>] [-DHINT=<text>]
#         -P check_image_symbols.cmake
# IMAGE_DIR checks every *.elf below the directory; REQUIRED names images that must be among
# them. Without NM, arm-none-eabi-nm is looked up on the PATH. A missing image or nm is a
# failure (with HINT, the command that builds the images).
# Run after every link (firmware/CMakeLists.txt) and by ctest (tests/firmware).
cmake_minimum_required(VERSION 3.25)

set(forbidden malloc _malloc_r free _free_r realloc calloc _sbrk _sbrk_r
              __cxa_throw __cxa_allocate_exception __cxa_begin_catch __gxx_personality_v0
              _Unwind_Resume _Unwind_RaiseException)

if(NOT DEFINED HINT)
  set(HINT "")
endif()
if(NOT DEFINED NM OR NM STREQUAL "")
  find_program(NM arm-none-eabi-nm)
endif()
if(NOT NM)
  message(FATAL_ERROR "arm-none-eabi-nm not found: run scripts/install-deps "
                      "(package gcc-arm-none-eabi, which brings binutils-arm-none-eabi)")
endif()

set(images "")
if(DEFINED IMAGE)
  if(NOT EXISTS "${IMAGE}")
    message(FATAL_ERROR "firmware image ${IMAGE} does not exist: ${HINT}")
  endif()
  list(APPEND images "${IMAGE}")
endif()
if(DEFINED IMAGE_DIR)
  file(GLOB_RECURSE found "${IMAGE_DIR}/*.elf")
  list(APPEND images ${found})
  if(DEFINED REQUIRED)
    string(REPLACE "," ";" required "${REQUIRED}")
    foreach(name IN LISTS required)
      if(NOT EXISTS "${IMAGE_DIR}/${name}")
        message(FATAL_ERROR "firmware image ${IMAGE_DIR}/${name} does not exist: ${HINT}")
      endif()
    endforeach()
  endif()
endif()
if(images STREQUAL "")
  message(FATAL_ERROR "no firmware image to check (IMAGE or IMAGE_DIR): ${HINT}")
endif()

list(JOIN forbidden "|" pattern)
set(bad 0)
foreach(image IN LISTS images)
  execute_process(COMMAND "${NM}" "${image}" OUTPUT_VARIABLE symbols ERROR_VARIABLE err
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${NM} ${image} failed (${rc}): ${err}")
  endif()
  # nm lines: "<address> <type> <name>", or "         U <name>" for an undefined symbol
  string(REGEX MATCHALL "[ \t][A-Za-z] (${pattern})\n" hits "${symbols}")
  if(hits)
    list(TRANSFORM hits STRIP)
    list(REMOVE_DUPLICATES hits)
    list(JOIN hits ", " hits)
    message(SEND_ERROR "${image}: heap or exception symbols present (nm type and name): ${hits}")
    math(EXPR bad "${bad} + 1")
  else()
    string(REGEX MATCHALL "\n" lines "\n${symbols}")
    list(LENGTH lines n)
    message(STATUS "${image}: none of ${pattern} among ${n} symbols")
  endif()
endforeach()
if(bad GREATER 0)
  message(FATAL_ERROR "${bad} image(s) contain heap or exception symbols")
endif()
