// SPDX-License-Identifier: Apache-2.0
// The pin table applied to the target's memory-mapped GPIO registers.
#include "pins.hpp"

namespace palp::stm32::pins {

void init_target() {
  Mmio io;
  init(io, kPins);
}

}  // namespace palp::stm32::pins
