// SPDX-License-Identifier: Apache-2.0
// The control-loop timers on the target's memory-mapped registers.
#include "timers.hpp"

namespace palp::stm32::timers {

Status init_bridge_pwm_target(std::uint32_t pwm_hz) {
  Mmio io;
  return init_bridge_pwm(io, pwm_hz);
}

void init_encoder_target() {
  Mmio io;
  init_encoder(io);
}

Status start_watchdog_target() {
  Mmio io;
  return start_watchdog(io);
}

}  // namespace palp::stm32::timers
