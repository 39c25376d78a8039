// SPDX-License-Identifier: Apache-2.0
// The analog front end on the target's memory-mapped registers, with the DMA's fixed buffer.
#include "adc.hpp"

namespace palp::stm32::adc {
namespace {

// Written by DMA1 channel 1 only; aligned for the 16-bit transfers.
alignas(4) volatile std::uint16_t g_pressure_codes[kPressureCount] = {};

}  // namespace

Status init_target() {
  Mmio io;
  return init(io, static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(g_pressure_codes)));
}

void start_pressure_scan_target() {
  Mmio io;
  start_pressure_scan(io);
}

InjectedCodes take_injected_target() {
  Mmio io;
  return take_injected(io);
}

const volatile std::uint16_t* pressure_codes_target() { return g_pressure_codes; }

}  // namespace palp::stm32::adc
