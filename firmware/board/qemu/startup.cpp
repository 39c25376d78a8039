// SPDX-License-Identifier: Apache-2.0
// Vector table and reset handler for QEMU's mps2-an386 (Cortex-M4F).
//
// Vector table layout: ARMv7-M Architecture Reference Manual (ARM DDI 0403E), B1.5.2-B1.5.3
// (exception numbers 1-15, then external interrupts; word 0 is the initial main stack pointer).
// mps2-an386 has 32 external interrupts (reference/qemu-icount.md, "The machine").
// This file must be compiled with -fno-tree-loop-distribute-patterns (firmware/CMakeLists.txt):
// otherwise GCC turns the copy and zero loops below into memcpy/memset calls.
#include <cstddef>
#include <cstdint>

#include "board.hpp"
#include "scb.hpp"

int main();

extern "C" {
// Symbols of the linker script (mps2_an386.ld).
extern std::uint32_t __data_start[];
extern std::uint32_t __data_end[];
extern const std::uint32_t __data_load[];
extern std::uint32_t __bss_start[];
extern std::uint32_t __bss_end[];
extern std::uint32_t __stack_top[];
extern void (*const __init_array_start[])();
extern void (*const __init_array_end[])();

[[noreturn]] void palp_reset_handler();
[[noreturn]] void palp_unexpected_exception();

// The interrupts an image may handle: weak, so an image that defines none of them (the test
// images) keeps the unexpected-exception handler there. IRQ numbers: QEMU hw/arm/mps2.c (UART0
// receive 0 and transmit 1, timer 0 IRQ 8; cmsdk_uart.hpp, cmsdk_timer.hpp).
[[gnu::weak]] void palp_irq_uart0_rx() { palp_unexpected_exception(); }
[[gnu::weak]] void palp_irq_uart0_tx() { palp_unexpected_exception(); }
[[gnu::weak]] void palp_irq_timer0() { palp_unexpected_exception(); }
}

namespace {

using Handler = void (*)();
constexpr std::size_t kExternalInterrupts = 32;
constexpr std::size_t kSystemExceptions = 15;  // exception numbers 1-15

struct VectorTable {
  void* initial_sp;
  Handler system[kSystemExceptions];
  Handler external[kExternalInterrupts];
};

constexpr Handler kUnexpected = palp_unexpected_exception;

void write_text(const char* s) {
  std::size_t n = 0;
  while (s[n] != '\0') ++n;
  palp::board::console_write(s, n);
}

}  // namespace

// Every exception other than reset is unexpected in a test image: it ends the run with exit code
// 3 and names the exception, so a fault fails a test at once instead of at its timeout. The
// firmware image handles the three interrupts above (qemu_board.cpp).
extern "C" [[gnu::section(".isr_vector"), gnu::used]] const VectorTable palp_vector_table = {
    __stack_top,
    {
        palp_reset_handler,  //  1 Reset
        kUnexpected,         //  2 NMI
        kUnexpected,         //  3 HardFault
        kUnexpected,         //  4 MemManage
        kUnexpected,         //  5 BusFault
        kUnexpected,         //  6 UsageFault
        nullptr,             //  7 reserved
        nullptr,             //  8 reserved
        nullptr,             //  9 reserved
        nullptr,             // 10 reserved
        kUnexpected,         // 11 SVCall
        kUnexpected,         // 12 DebugMonitor
        nullptr,             // 13 reserved
        kUnexpected,         // 14 PendSV
        kUnexpected,         // 15 SysTick
    },
    {
        palp_irq_uart0_rx, palp_irq_uart0_tx, kUnexpected, kUnexpected,  // IRQ 0-3
        kUnexpected, kUnexpected, kUnexpected, kUnexpected,              // IRQ 4-7
        palp_irq_timer0, kUnexpected, kUnexpected, kUnexpected,          // IRQ 8-11
        kUnexpected, kUnexpected, kUnexpected, kUnexpected, kUnexpected, kUnexpected,
        kUnexpected, kUnexpected, kUnexpected, kUnexpected, kUnexpected, kUnexpected,
        kUnexpected, kUnexpected, kUnexpected, kUnexpected, kUnexpected, kUnexpected,
        kUnexpected, kUnexpected,
    },
};

void palp_reset_handler() {
  // The FPU first: compiled code may use the VFP registers anywhere (scb.hpp).
  palp::board::scb::cpacr() |= palp::board::scb::kCpacrCp10Cp11Full;
  asm volatile("dsb\n isb" ::: "memory");

  // .data: QEMU loads it at its load address in flash; copy it to RAM. Then zero .bss.
  const std::uint32_t* src = __data_load;
  for (std::uint32_t* dst = __data_start; dst < __data_end;) *dst++ = *src++;
  for (std::uint32_t* dst = __bss_start; dst < __bss_end;) *dst++ = 0;

  palp::board::stack_paint();
  for (auto* ctor = __init_array_start; ctor < __init_array_end; ++ctor) (*ctor)();

  palp::board::console_init();
  palp::board::exit(main());
}

void palp_unexpected_exception() {
  std::uint32_t ipsr;
  asm volatile("mrs %0, ipsr" : "=r"(ipsr));
  char digits[4] = {'0', '0', '0', '\0'};  // the exception number, 0-511
  for (int k = 2; k >= 0; --k, ipsr /= 10) digits[k] = static_cast<char>('0' + ipsr % 10);
  write_text("\npalp: unexpected exception ");
  write_text(digits);
  write_text(" (3 HardFault, 4 MemManage, 5 BusFault, 6 UsageFault)\n");
  palp::board::exit(3);
}
