// SPDX-License-Identifier: Apache-2.0
// The board the firmware app (firmware/app/src/main.cpp) is built for in this image: the
// STM32G474 probe controller (stm_board.hpp).
#pragma once

#include "stm_board.hpp"

namespace palp::app {
using TargetBoard = palp::stm32::StmBoard;
}  // namespace palp::app
