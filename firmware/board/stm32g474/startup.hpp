// SPDX-License-Identifier: Apache-2.0
// What the STM32G474 reset handler (startup.cpp) leaves for the application to read.
#pragma once

#include "clock.hpp"

namespace palp::stm32::startup {

/// The result of clock::init_target() at reset. On failure the reset handler carries on to
/// main() regardless: the controller runs on whatever clock the failed step left (HSI16 16 MHz if
/// the PLL never locked; see NOTES.md), and the application reports this status.
clock::Status clock_status();

}  // namespace palp::stm32::startup
