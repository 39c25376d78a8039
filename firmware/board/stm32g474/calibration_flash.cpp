// SPDX-License-Identifier: Apache-2.0
// The calibration store on the target's memory-mapped registers: instantiated here so that the
// cross build compiles every member (the board class holds one CalibrationFlash<Mmio>).
#include "calibration_flash.hpp"

template class palp::stm32::CalibrationFlash<palp::stm32::Mmio>;
