// SPDX-License-Identifier: Apache-2.0
// The STM32G474 vector table, in .isr_vector at the start of flash (stm32g474.ld).
//
// Layout: ARMv7-M Architecture Reference Manual (ARM DDI 0403E), B1.5.2-B1.5.3: word 0 the initial
// main stack pointer, exceptions 1-15, then the external interrupts. The interrupts are
// vectors_list.hpp's (ST's SVD, checked by tests/stm32/test_vectors.cpp): every one is a weak
// alias of palp_default_handler named after the IRQ (e.g. TIM1_UP_TIM16_IRQHandler), so a board
// file defines a handler by defining that name. System exceptions likewise (HardFault_Handler…).
#include <array>
#include <cstddef>
#include <cstdint>

#include "vectors_list.hpp"

extern "C" {
extern std::uint32_t __stack_top[];  // stm32g474.ld

[[noreturn]] void palp_reset_handler();  // startup.cpp
void palp_default_handler();

// The exception number (IPSR) of the last unexpected exception, for a debugger: 0 = none.
volatile std::uint32_t palp_unexpected_exception_number = 0;

#define PALP_WEAK_DEFAULT [[gnu::weak, gnu::alias("palp_default_handler")]]
PALP_WEAK_DEFAULT void NMI_Handler();
PALP_WEAK_DEFAULT void HardFault_Handler();
PALP_WEAK_DEFAULT void MemManage_Handler();
PALP_WEAK_DEFAULT void BusFault_Handler();
PALP_WEAK_DEFAULT void UsageFault_Handler();
PALP_WEAK_DEFAULT void SVC_Handler();
PALP_WEAK_DEFAULT void DebugMon_Handler();
PALP_WEAK_DEFAULT void PendSV_Handler();
PALP_WEAK_DEFAULT void SysTick_Handler();
#define PALP_DECLARE_IRQ_HANDLER(number, name) PALP_WEAK_DEFAULT void name##_IRQHandler();
PALP_STM32G474_IRQS(PALP_DECLARE_IRQ_HANDLER)
#undef PALP_DECLARE_IRQ_HANDLER
#undef PALP_WEAK_DEFAULT
}

namespace {

using Handler = void (*)();
using palp::stm32::vectors::kExternalSlots;

constexpr std::size_t kSystemExceptions = 15;  // exception numbers 1-15

struct VectorTable {
  void* initial_sp;
  Handler system[kSystemExceptions];
  std::array<Handler, kExternalSlots> external;
};

// The external slots by IRQ number; numbers the list skips (reserved, IRQ 85) stay null.
constexpr std::array<Handler, kExternalSlots> external_vectors() {
  std::array<Handler, kExternalSlots> slots{};
#define PALP_PLACE_IRQ_HANDLER(number, name) slots[number] = name##_IRQHandler;
  PALP_STM32G474_IRQS(PALP_PLACE_IRQ_HANDLER)
#undef PALP_PLACE_IRQ_HANDLER
  return slots;
}

}  // namespace

extern "C" [[gnu::section(".isr_vector"), gnu::used]] const VectorTable palp_vector_table = {
    __stack_top,
    {
        palp_reset_handler,  //  1 Reset
        NMI_Handler,         //  2 NMI
        HardFault_Handler,   //  3 HardFault
        MemManage_Handler,   //  4 MemManage
        BusFault_Handler,    //  5 BusFault
        UsageFault_Handler,  //  6 UsageFault
        nullptr,             //  7 reserved
        nullptr,             //  8 reserved
        nullptr,             //  9 reserved
        nullptr,             // 10 reserved
        SVC_Handler,         // 11 SVCall
        DebugMon_Handler,    // 12 DebugMonitor
        nullptr,             // 13 reserved
        PendSV_Handler,      // 14 PendSV
        SysTick_Handler,     // 15 SysTick
    },
    external_vectors(),
};

static_assert(sizeof(VectorTable) == (1 + kSystemExceptions + kExternalSlots) * 4,
              "the vector table is 118 words: SP, 15 exceptions, IRQ 0..101");

// An exception nothing handles: record its number and stop here (a debugger sees where; the
// watchdog, once started by the board, resets the controller).
void palp_default_handler() {
  std::uint32_t ipsr;
  asm volatile("mrs %0, ipsr" : "=r"(ipsr));
  palp_unexpected_exception_number = ipsr & 0x1FFu;
  while (true) {
    asm volatile("" ::: "memory");
  }
}
