// SPDX-License-Identifier: Apache-2.0
// Reset handler for the STM32G474 (Cortex-M4F): FPU, VTOR, memory set-up, constructors, clocks,
// then main(). The vector table is vectors.cpp's; the symbols are stm32g474.ld's.
//
// This file must be compiled with -fno-tree-loop-distribute-patterns (firmware/CMakeLists.txt):
// otherwise GCC turns the copy and zero loops below into memcpy/memset calls.
//
// System control registers: board/cortex_m/scb.hpp (VTOR takes the table's address, bits [31:7];
// 128-word aligned here; CPACR CP10/CP11 full access, then DSB, ISB).
//
// First of all, a bootloader request left by the board before its reset (bootloader_request.hpp,
// facts §1.4 pattern 1) enters the ROM: nothing else has run, so the chip is in its reset state.
#include <cstdint>

#include "bootloader_request.hpp"
#include "clock.hpp"
#include "scb.hpp"
#include "startup.hpp"

int main();

extern "C" {
extern std::uint32_t __data_start[];
extern std::uint32_t __data_end[];
extern const std::uint32_t __data_load[];
extern std::uint32_t __bss_start[];
extern std::uint32_t __bss_end[];
extern std::uint32_t __ccmram_start[];
extern std::uint32_t __ccmram_end[];
extern const std::uint32_t __ccmram_load[];
extern std::uint32_t __ccmram_bss_start[];
extern std::uint32_t __ccmram_bss_end[];
extern void (*const __init_array_start[])();
extern void (*const __init_array_end[])();
extern const std::uint32_t palp_vector_table[];  // vectors.cpp

[[noreturn]] void palp_reset_handler();
}

// In .bss, so at or above 0x2000_4000 after the stack (bootloader_request.hpp); the reset handler
// reads it before .bss is zeroed.
volatile std::uint32_t palp_bootloader_request[2];

namespace {

void copy(std::uint32_t* dst, std::uint32_t* end, const std::uint32_t* src) {
  while (dst < end) *dst++ = *src++;
}

void zero(std::uint32_t* dst, std::uint32_t* end) {
  while (dst < end) *dst++ = 0;
}

// Zeroed with .bss (Status::ok is 0), then set by the reset handler after the clock init.
palp::stm32::clock::Status g_clock_status = palp::stm32::clock::Status::ok;

}  // namespace

palp::stm32::clock::Status palp::stm32::startup::clock_status() { return g_clock_status; }

void palp_reset_handler() {
  if (palp_bootloader_request[0] == palp::stm32::bootloader::kRequestWord0 &&
      palp_bootloader_request[1] == palp::stm32::bootloader::kRequestWord1) {
    palp_bootloader_request[0] = 0;  // once: the ROM's exit (DFU leave) resets into the app
    palp_bootloader_request[1] = 0;
    const auto* rom = reinterpret_cast<const volatile std::uint32_t*>(
        static_cast<std::uintptr_t>(palp::stm32::bootloader::kSystemMemory));
    const std::uint32_t rom_sp = rom[0];
    const std::uint32_t rom_reset = rom[1];
    asm volatile("msr msp, %0\n bx %1" ::"r"(rom_sp), "r"(rom_reset) : "memory");
    __builtin_unreachable();
  }
  // The FPU first: compiled code may use the VFP registers anywhere.
  palp::board::scb::cpacr() = palp::board::scb::cpacr() | palp::board::scb::kCpacrCp10Cp11Full;
  // The table in flash, wherever the boot mode mapped it (0x0 alias or 0x08000000).
  palp::board::scb::vtor() =
      static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(palp_vector_table));
  asm volatile("dsb\n isb" ::: "memory");

  copy(__data_start, __data_end, __data_load);
  copy(__ccmram_start, __ccmram_end, __ccmram_load);  // .ccmram_text and .ccmram_data
  zero(__bss_start, __bss_end);
  zero(__ccmram_bss_start, __ccmram_bss_end);

  for (auto* ctor = __init_array_start; ctor < __init_array_end; ++ctor) (*ctor)();

  // 170 MHz + HSI48/CRS. A failure is not fatal here: the status is kept for the application
  // to report (startup.hpp), and main() runs on the clock the failed step left.
  g_clock_status = palp::stm32::clock::init_target();

  main();
  while (true) {  // main() does not return on the target; if it does, stop here.
    asm volatile("" ::: "memory");
  }
}
