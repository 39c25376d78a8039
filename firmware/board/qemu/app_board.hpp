// SPDX-License-Identifier: Apache-2.0
// The board the firmware app (firmware/app/src/main.cpp) is built for in this image.
#pragma once

#include "qemu_board.hpp"

namespace palp::app {
using TargetBoard = palp::qemu::QemuBoard;
}  // namespace palp::app
