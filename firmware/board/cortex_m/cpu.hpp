// SPDX-License-Identifier: Apache-2.0
// The Cortex-M core operations a board needs besides memory-mapped registers: PRIMASK (mask and
// restore every interrupt), WFI, and the DSB/ISB barriers; as a policy class, so a board written
// as a template (the STM32G474's StmBoardT) runs on the host with a fake that records the calls.
//
// Sources: [ARM] ARMv7-M Architecture Reference Manual (ARM DDI 0403E): the special-purpose mask
// register PRIMASK (CPSID i / CPSIE i, MRS/MSR), the WFI instruction and its wake-up rule (a
// pending interrupt that PRIMASK masks still ends the sleep; it is taken at the CPSIE), the DSB and
// ISB barriers; [GUG] Cortex-M4 Devices Generic User Guide (ARM DUI 0553): its WFI page, and
// 4.2.9 (DSB/ISB after masking an interrupt in the NVIC).
#pragma once

#include <cstdint>

namespace palp::board {

#if defined(__arm__)
struct CortexM {
  /// Masks every interrupt (CPSID i) and returns the previous PRIMASK for restore().
  std::uint32_t mask_interrupts() {
    std::uint32_t primask;
    asm volatile("mrs %0, primask\n cpsid i" : "=r"(primask)::"memory");
    return primask;
  }
  void restore_interrupts(std::uint32_t primask) {
    asm volatile("msr primask, %0" ::"r"(primask) : "memory");
  }
  void disable_interrupts() { asm volatile("cpsid i" ::: "memory"); }
  void enable_interrupts() { asm volatile("cpsie i" ::: "memory"); }
  /// Sleeps until an interrupt is pending (also when PRIMASK masks it).
  void wait_for_interrupt() { asm volatile("dsb\n wfi" ::: "memory"); }
  /// DSB + ISB: earlier register writes have taken effect before the next instruction.
  void barrier() { asm volatile("dsb\n isb" ::: "memory"); }
  /// After a reset request: waits for the reset (does not return).
  [[noreturn]] void wait_for_reset() {
    asm volatile("dsb" ::: "memory");
    for (;;) asm volatile("" ::: "memory");
  }
};
#endif

/// Masks every interrupt for its lifetime and restores the previous state (Cpu: a policy with
/// mask_interrupts()/restore_interrupts(), e.g. CortexM).
template <class Cpu>
class InterruptLock {
 public:
  explicit InterruptLock(Cpu& cpu) : cpu_(cpu), primask_(cpu.mask_interrupts()) {}
  ~InterruptLock() { cpu_.restore_interrupts(primask_); }
  InterruptLock(const InterruptLock&) = delete;
  InterruptLock& operator=(const InterruptLock&) = delete;

 private:
  Cpu& cpu_;
  std::uint32_t primask_;
};

}  // namespace palp::board
