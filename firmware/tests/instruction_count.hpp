// SPDX-License-Identifier: Apache-2.0
// Counting the instructions a piece of code runs, for the cost images under
// `qemu-system-arm -icount shift=0` (reference/qemu-icount.md): SysTick counts them, 40 per count
// (board/qemu/systick.hpp). Shared by palp-tick-cost and palp-usb-cost.
#pragma once

#include <cstdint>

#include "systick.hpp"

namespace palp::cost {


/// Keeps the compiler from moving memory accesses across this point, and v's computation after
/// it (code that touches no volatile may otherwise move across the SysTick reads).
template <class T>
void barrier(const T& v) {
  asm volatile("" : : "r"(&v) : "memory");
}

/// The cost of one now()/now() pair in SysTick counts, subtracted from every reading.
inline std::uint32_t overhead_counts = 0;

/// Starts SysTick and measures overhead_counts; call once before instructions_of().
inline void start_counting() {
  board::systick::start();
  const std::uint32_t a = board::systick::now();
  barrier(a);
  const std::uint32_t b = board::systick::now();
  overhead_counts = board::systick::elapsed(a, b);
}

/// The instructions f() ran (a multiple of kInstructionsPerCount).
template <class F>
std::uint32_t instructions_of(F&& f) {
  const std::uint32_t a = board::systick::now();
  barrier(a);
  f();
  barrier(a);
  const std::uint32_t b = board::systick::now();
  const std::uint32_t t = board::systick::elapsed(a, b);
  return (t > overhead_counts ? t - overhead_counts : 0) * board::systick::kInstructionsPerCount;
}

}  // namespace palp::cost
