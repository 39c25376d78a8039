// SPDX-License-Identifier: Apache-2.0
// The target's StmBoard (stm_board.hpp): StmBoardT on the memory-mapped registers and the core.
#include "stm_board.hpp"

#include "startup.hpp"

#ifndef PALP_GIT_HASH
#define PALP_GIT_HASH "unknown"
#endif

namespace palp::stm32 {
namespace {

Mmio g_io;
board::CortexM g_cpu;

BoardPlatform target_platform() {
  BoardPlatform p;
  p.pressure_codes = adc::pressure_codes_target();
  p.pressure_codes_address =
      static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(adc::pressure_codes_target()));
  p.bootloader_request_address =
      static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(palp_bootloader_request));
  p.git_hash = PALP_GIT_HASH;
  return p;
}

}  // namespace

StmBoard::StmBoard() : StmBoardT(g_io, g_cpu, link_uart::host_link(), target_platform()) {
  set_irq_board(this);
  init(startup::clock_status() == clock::Status::ok);
}

}  // namespace palp::stm32
