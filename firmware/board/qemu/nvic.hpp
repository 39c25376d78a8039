// The Cortex-M4 NVIC registers the QEMU board uses: enabling, masking and prioritising single
// external interrupts (the tick guard masks only the control tick's interrupt).
//
// Sources:
//   [ARM] ARMv7-M Architecture Reference Manual (ARM DDI 0403E), B3.4 "Nested Vectored
//         Interrupt Controller, NVIC": NVIC_ISER0 0xE000E100 (write 1 to enable), NVIC_ICER0
//         0xE000E180 (write 1 to disable), NVIC_ISPR0 0xE000E200 (write 1 to set pending),
//         NVIC_ICPR0 0xE000E280 (write 1 to clear pending),
//         NVIC_IPR0 0xE000E400 (one priority byte per interrupt, lower value = more urgent;
//         an implementation keeps only the top bits, at least 3 on ARMv7-M).
//   [GUG] Cortex-M4 Devices Generic User Guide (ARM DUI 0553), 4.2 "Nested Vectored Interrupt
//         Controller" (the same addresses; the M4 implements at least 3 priority bits) and 4.2.9
//         on the DSB/ISB after disabling an interrupt before relying on it being masked.
#pragma once

#include <cstdint>

namespace palp::board::nvic {

inline constexpr std::uintptr_t kIser0 = 0xE000E100u;  // [ARM] B3.4.4
inline constexpr std::uintptr_t kIcer0 = 0xE000E180u;  // [ARM] B3.4.5
inline constexpr std::uintptr_t kIspr0 = 0xE000E200u;  // [ARM] B3.4.6
inline constexpr std::uintptr_t kIcpr0 = 0xE000E280u;  // [ARM] B3.4.7
inline constexpr std::uintptr_t kIpr0 = 0xE000E400u;   // [ARM] B3.4.9

inline volatile std::uint32_t& word(std::uintptr_t a) {
  return *reinterpret_cast<volatile std::uint32_t*>(a);
}

/// Priorities used by the board, in the top 2 bits so that any implemented width keeps them
/// distinct [ARM], [GUG]: lower is more urgent.
inline constexpr std::uint8_t kPriorityClock = 0x00;  // the clock's wrap count: never waits
inline constexpr std::uint8_t kPriorityTick = 0x40;   // the control tick
inline constexpr std::uint8_t kPriorityLink = 0x80;   // UART receive / transmit

inline void set_priority(std::uint32_t irq, std::uint8_t priority) {
  *reinterpret_cast<volatile std::uint8_t*>(kIpr0 + irq) = priority;
}
inline void enable(std::uint32_t irq) { word(kIser0 + 4 * (irq / 32)) = 1u << (irq % 32); }
/// Disables the interrupt; after the DSB/ISB it can no longer be taken [GUG] 4.2.9.
inline void disable(std::uint32_t irq) {
  word(kIcer0 + 4 * (irq / 32)) = 1u << (irq % 32);
  asm volatile("dsb\n isb" ::: "memory");
}
inline void set_pending(std::uint32_t irq) { word(kIspr0 + 4 * (irq / 32)) = 1u << (irq % 32); }
inline void clear_pending(std::uint32_t irq) { word(kIcpr0 + 4 * (irq / 32)) = 1u << (irq % 32); }

}  // namespace palp::board::nvic
