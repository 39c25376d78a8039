// SPDX-License-Identifier: Apache-2.0
// The clock init on the target's memory-mapped registers.
#include "clock.hpp"

namespace palp::stm32::clock {

Status init_target() {
  Mmio io;
  return init(io);
}

}  // namespace palp::stm32::clock
