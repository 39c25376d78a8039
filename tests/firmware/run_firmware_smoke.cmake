# SPDX-License-Identifier: Apache-2.0
# Smoke test of the firmware image under QEMU: the image boots, serves the SDK over UART0 on a
# TCP chardev, and holds a current. Passes only when
#   - palpctl info reads a compatible handshake, board qemu-mps2-an386 and the advertised
#     max_stream_rate_Hz (EXPECT_MAX_RATE_HZ),
#   - palpctl run hold at 0.3 A for 1 s completes and the measured current of its last half
#     second averages 0.3 A within 10 mA,
#   - QEMU is still running after them (the image neither faulted nor exited),
#   - an EnterBootloader request then ends QEMU with the board's exit status 42.
#
#   cmake -DIMAGE=<elf> -DPALPCTL=<palpctl> -DWORK_DIR=<dir> -DEXPECT_MAX_RATE_HZ=<n>
#         [-DLINK=tcp|pty] [-DHINT=<text>] -P run_firmware_smoke.cmake
#
# LINK=pty (a UART board's path: the SDK's serial:// over a tty) gives UART0 to a pseudo-terminal
# (`-serial pty`, whose name QEMU prints) and connects with serial:///dev/pts/N?baud=4000000 (a
# pty ignores the baud; the SDK budgets a stream by it, and 1 kHz of every channel needs more
# than 115200 baud carries); the bootloader request is written to the pty.
#
# QEMU runs with the command line of firmware/README.md on a free port (a random one, retried
# when it is taken), every step under `timeout`, so a hang fails instead of waiting forever; QEMU
# is killed at the end whatever happened. A missing image, QEMU or palpctl is a failure. The
# bootloader request is sent by bash's /dev/tcp (palpctl has no such command).
cmake_minimum_required(VERSION 3.25)

foreach(var IMAGE PALPCTL WORK_DIR EXPECT_MAX_RATE_HZ)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_firmware_smoke.cmake: -D${var}=... is required")
  endif()
endforeach()
include(${CMAKE_CURRENT_LIST_DIR}/find_qemu.cmake)
if(NOT EXISTS "${PALPCTL}")
  message(FATAL_ERROR "palpctl ${PALPCTL} does not exist: build the palpctl target")
endif()
file(MAKE_DIRECTORY "${WORK_DIR}")
set(qemu_log "${WORK_DIR}/qemu.log")
if(NOT DEFINED LINK)
  set(LINK tcp)
endif()
if(NOT LINK MATCHES "^(tcp|pty)$")
  message(FATAL_ERROR "run_firmware_smoke.cmake: LINK must be tcp or pty, not '${LINK}'")
endif()

# ---- QEMU on a pseudo-terminal ------------------------------------------------------------------
set(qemu_pid "")
if(LINK STREQUAL "pty")
  file(REMOVE "${WORK_DIR}/qemu.pid" "${WORK_DIR}/qemu.rc" "${qemu_log}")
  execute_process(
    COMMAND sh -c "( \"$0\" 120 \"$1\" -M mps2-an386 -display none -monitor none -semihosting-config enable=on,target=native -serial pty -kernel \"$2\" >\"$3\" 2>&1 </dev/null & echo $! >\"$4.pid\"; wait $!; echo $? >\"$4.rc\" ) >/dev/null 2>&1 &"
            "${TIMEOUT}" "${QEMU}" "${IMAGE}" "${qemu_log}" "${WORK_DIR}/qemu")
  set(tty "")
  foreach(wait RANGE 1 100)
    execute_process(COMMAND sleep 0.1)
    if(EXISTS "${qemu_log}")
      file(READ "${qemu_log}" log)
      if(log MATCHES "char device redirected to (/dev/pts/[0-9]+)")
        set(tty "${CMAKE_MATCH_1}")
        break()
      endif()
    endif()
  endforeach()
  if(EXISTS "${WORK_DIR}/qemu.pid")
    file(READ "${WORK_DIR}/qemu.pid" qemu_pid)
    string(STRIP "${qemu_pid}" qemu_pid)
  endif()
  if(tty STREQUAL "" OR qemu_pid STREQUAL "")
    if(NOT qemu_pid STREQUAL "")
      execute_process(COMMAND kill ${qemu_pid} ERROR_QUIET)
    endif()
    message(FATAL_ERROR "QEMU named no pseudo-terminal within 10 s; its output: ${log}")
  endif()
  set(uri "serial://${tty}?baud=4000000")
endif()

# ---- QEMU on a free port ------------------------------------------------------------------------
foreach(attempt RANGE 1 8)
  if(LINK STREQUAL "pty")
    break()
  endif()
  string(RANDOM LENGTH 4 ALPHABET 0123456789 r)
  math(EXPR port "20000 + (1${r} - 10000) * 4")  # the 1 keeps a leading 0 from reading as octal
  # backgrounded by sh with its output in a file, so execute_process returns at once; a subshell
  # writes QEMU's (timeout's) pid and, when it ends, its exit status into files
  file(REMOVE "${WORK_DIR}/qemu.pid" "${WORK_DIR}/qemu.rc")
  execute_process(
    COMMAND sh -c "( \"$0\" 120 \"$1\" -M mps2-an386 -display none -monitor none -semihosting-config enable=on,target=native -serial tcp:127.0.0.1:$2,server=on,wait=off -kernel \"$3\" >\"$4\" 2>&1 </dev/null & echo $! >\"$5.pid\"; wait $!; echo $? >\"$5.rc\" ) >/dev/null 2>&1 &"
            "${TIMEOUT}" "${QEMU}" "${port}" "${IMAGE}" "${qemu_log}" "${WORK_DIR}/qemu")
  set(pid "")
  foreach(wait RANGE 1 50)
    execute_process(COMMAND sleep 0.1)
    if(EXISTS "${WORK_DIR}/qemu.pid")
      file(READ "${WORK_DIR}/qemu.pid" pid)
      string(STRIP "${pid}" pid)
      break()
    endif()
  endforeach()
  if(pid STREQUAL "")
    message(FATAL_ERROR "the shell that starts QEMU wrote no pid within 5 s")
  endif()
  execute_process(COMMAND sleep 0.5)
  execute_process(COMMAND kill -0 ${pid} RESULT_VARIABLE dead)
  if(dead EQUAL 0)
    set(qemu_pid ${pid})
    break()
  endif()
  file(READ "${qemu_log}" log)
  message(STATUS "QEMU did not stay up on port ${port} (${log}); another port")
endforeach()
if(qemu_pid STREQUAL "")
  message(FATAL_ERROR "QEMU did not start on any of 8 ports; its last words: ${log}")
endif()
if(LINK STREQUAL "tcp")
  set(uri "tcp://127.0.0.1:${port}")
endif()
message(STATUS "QEMU (pid ${qemu_pid}) serves the image on ${uri}")

set(failure "")
macro(fail text)
  if(failure STREQUAL "")
    set(failure "${text}")
  endif()
endmacro()

# ---- Hello and DeviceInfo -----------------------------------------------------------------------
execute_process(COMMAND ${TIMEOUT} 30 ${PALPCTL} --uri ${uri} --json info
                OUTPUT_VARIABLE info ERROR_VARIABLE info_err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  fail("palpctl info exited ${rc} (124: timed out): ${info_err}${info}")
else()
  string(JSON board GET "${info}" device board)
  string(JSON max_rate GET "${info}" device max_stream_rate_Hz)
  string(JSON verdict GET "${info}" handshake verdict)
  message(STATUS "info: board ${board}, max_stream_rate_Hz ${max_rate}, handshake ${verdict}")
  if(NOT board STREQUAL "qemu-mps2-an386")
    fail("DeviceInfo.board is '${board}', not qemu-mps2-an386")
  elseif(NOT max_rate EQUAL EXPECT_MAX_RATE_HZ)
    fail("DeviceInfo.max_stream_rate_Hz is ${max_rate}, not ${EXPECT_MAX_RATE_HZ}")
  elseif(NOT verdict STREQUAL "compatible")
    fail("the handshake's verdict is '${verdict}', not compatible")
  endif()
endif()

# ---- a 0.3 A hold, streamed -----------------------------------------------------------------------
# A decimal text (the CSV's amperes) as integer microamperes, for CMake's integer arithmetic.
function(to_micro text out)
  if(NOT text MATCHES "^(-?)([0-9]+)(\\.([0-9]*))?$")
    set(${out} "" PARENT_SCOPE)
    return()
  endif()
  set(sign "${CMAKE_MATCH_1}")
  set(frac "${CMAKE_MATCH_4}000000")
  string(SUBSTRING "${frac}" 0 6 frac)
  math(EXPR v "${CMAKE_MATCH_2} * 1000000 + 1${frac} - 1000000")
  set(${out} "${sign}${v}" PARENT_SCOPE)
endfunction()

if(failure STREQUAL "")
  set(csv "${WORK_DIR}/hold.csv")
  execute_process(COMMAND ${TIMEOUT} 60 ${PALPCTL} --uri ${uri} run hold --current-A 0.3
                          --seconds 1 --rate-Hz 1000 --out ${csv} --overwrite
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    fail("palpctl run hold exited ${rc} (124: timed out): ${err}${out}")
  else()
    # columns: sample_index,t_s,i_cmd_A,i_A,...; the hold's samples have i_cmd_A 0.3
    file(STRINGS "${csv}" rows)
    set(held "")
    foreach(row IN LISTS rows)
      string(REPLACE "," ";" f "${row}")
      list(GET f 2 i_cmd)
      if(i_cmd STREQUAL "0.3")
        list(GET f 3 i)
        list(APPEND held "${i}")
      endif()
    endforeach()
    list(LENGTH held n)
    if(n LESS 900)
      fail("the recording has ${n} samples at i_cmd_A 0.3, not the hold's ~1000 (${csv})")
    else()
      math(EXPR first "${n} / 2")
      set(sum 0)
      set(count 0)
      foreach(k RANGE ${first} ${n})
        if(k LESS n)
          list(GET held ${k} i)
          to_micro("${i}" u)
          math(EXPR sum "${sum} + ${u}")
          math(EXPR count "${count} + 1")
        endif()
      endforeach()
      math(EXPR mean_uA "${sum} / ${count}")
      message(STATUS "hold: ${n} samples at 0.3 A commanded; the last ${count} average ${mean_uA} uA")
      math(EXPR err_uA "${mean_uA} - 300000")
      if(err_uA LESS -10000 OR err_uA GREATER 10000)
        fail("the held current averages ${mean_uA} uA, not 300000 +- 10000 uA")
      endif()
    endif()
  endif()
endif()

# ---- QEMU still up; the bootloader request ends it with status 42 --------------------------------
execute_process(COMMAND kill -0 ${qemu_pid} RESULT_VARIABLE gone)
if(NOT gone EQUAL 0)
  fail("QEMU exited during the test (the image faulted or exited)")
elseif(failure STREQUAL "")
  # EnterBootloader{magic 0x544F4F42}, seq 7, protocol 1.1: header 01 01 04 00 07 00 04 00,
  # payload 42 4f 4f 54, CRC-32 e8 7d 22 d9, COBS-encoded with its 00 delimiter (SPEC.md §4;
  # made like the EnterBootloader vector of protocol/vectors/messages.txt)
  set(frame "\\x04\\x01\\x01\\x04\\x02\\x07\\x02\\x04\\x09\\x42\\x4f\\x4f\\x54\\xd9\\x22\\x7d\\xe8\\x00")
  if(LINK STREQUAL "pty")
    # the tty raw (no tab expansion of the frame's 0x09) and held open 2 s: QEMU reads a pty only
    # while a slave is open, and notices one within a second
    execute_process(COMMAND ${TIMEOUT} 10 bash -c "exec 3<>\"$0\" && stty raw -echo <&3 && printf \"$1\" >&3 && sleep 2"
                            ${tty} ${frame}
                    RESULT_VARIABLE rc ERROR_VARIABLE err)
  else()
    execute_process(COMMAND ${TIMEOUT} 10 bash -c "exec 3<>/dev/tcp/127.0.0.1/$0 && printf \"$1\" >&3 && cat <&3 >/dev/null"
                            ${port} ${frame}
                    RESULT_VARIABLE rc ERROR_VARIABLE err)
  endif()
  set(status "")
  foreach(wait RANGE 1 50)
    if(EXISTS "${WORK_DIR}/qemu.rc")
      file(READ "${WORK_DIR}/qemu.rc" status)
      string(STRIP "${status}" status)
      break()
    endif()
    execute_process(COMMAND sleep 0.1)
  endforeach()
  message(STATUS "EnterBootloader: QEMU exit status '${status}'")
  if(NOT status STREQUAL "42")
    fail("after EnterBootloader QEMU's exit status is '${status}', not 42 (bash: rc ${rc} ${err})")
  endif()
endif()
execute_process(COMMAND kill ${qemu_pid} ERROR_QUIET)
file(READ "${qemu_log}" log)
if(NOT failure STREQUAL "")
  message(FATAL_ERROR "${failure}\nQEMU's output: ${log}")
endif()
message(STATUS "firmware smoke test passed on ${uri}")
