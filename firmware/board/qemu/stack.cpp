// SPDX-License-Identifier: Apache-2.0
// Stack high-water mark: startup paints the free stack with a pattern; the deepest word that
// no longer holds it marks the most stack ever used. The stack's bounds come from the linker
// script (mps2_an386.ld).
#include <cstdint>

#include "board.hpp"

extern "C" {
extern std::uint32_t __stack_bottom[];
extern std::uint32_t __stack_top[];
}

namespace palp::board {

namespace {
constexpr std::uint32_t kPaint = 0xC5AC5AC5u;
}  // namespace

void stack_paint() {
  std::uint32_t* sp;
  asm volatile("mov %0, sp" : "=r"(sp));
  // Everything below sp is free; keep a few words' margin below this function's frame.
  for (std::uint32_t* p = __stack_bottom; p + 8 < sp; ++p) *p = kPaint;
}

std::size_t stack_size() {
  return static_cast<std::size_t>(__stack_top - __stack_bottom) * sizeof(std::uint32_t);
}

std::size_t stack_used() {
  const std::uint32_t* p = __stack_bottom;
  while (p < __stack_top && *p == kPaint) ++p;
  return static_cast<std::size_t>(__stack_top - p) * sizeof(std::uint32_t);
}

}  // namespace palp::board
