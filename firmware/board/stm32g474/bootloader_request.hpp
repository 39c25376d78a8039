// SPDX-License-Identifier: Apache-2.0
// Entering the ROM bootloader (stm32g474-facts.md §1.4, pattern 1 "flag + reset, jump early after
// reset"): the board (stm_board.hpp, enter_bootloader) writes a 64-bit request into RAM and asks
// for a system reset (AIRCR.SYSRESETREQ, board/cortex_m/scb.hpp); the reset handler
// (startup.cpp) checks the request before anything else, clears it, loads MSP from the system
// memory's first word and branches to its second (the ROM's reset vector). After a reset the chip
// is in its reset state, so clocks, NVIC, USB and a software-started IWDG are already clean.
//
// Where the request lives: `palp_bootloader_request`, two words in .bss, which the linker script
// places after the 16 KiB stack, i.e. at or above 0x2000_4000 (the ROM uses SRAM 0x2000_0000 ..
// 0x2000_3FFF, facts §1.4). The reset handler reads it before zeroing .bss; SRAM keeps its content
// across a system reset. 64 bits so that power-up SRAM content does not pass for a request.
#pragma once

#include <cstdint>

namespace palp::stm32::bootloader {

inline constexpr std::uint32_t kRequestWord0 = 0x504C'4150u;  // "PALP" (little-endian bytes)
inline constexpr std::uint32_t kRequestWord1 = 0x2155'4644u;  // "DFU!"
/// The system memory (ROM bootloader): its initial MSP at +0 and reset vector at +4 (facts §1.1,
/// §1.4).
inline constexpr std::uint32_t kSystemMemory = 0x1FFF'0000u;
/// The request must not lie below this (the ROM's own RAM, facts §1.4).
inline constexpr std::uint32_t kLowestRequestAddress = 0x2000'4000u;

}  // namespace palp::stm32::bootloader

/// The request's two words (startup.cpp defines them, in .bss).
extern "C" volatile std::uint32_t palp_bootloader_request[2];
