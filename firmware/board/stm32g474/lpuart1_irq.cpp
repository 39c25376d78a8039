// SPDX-License-Identifier: Apache-2.0
// The target's host link object and its interrupt handler (link_uart.hpp). The handler replaces
// vectors.cpp's weak default of the same name (vectors_list.hpp: IRQ 91 `LPUART`).
#include "link_uart.hpp"

namespace palp::stm32::link_uart {
namespace {
Mmio g_mmio;
constinit HostLink g_link{g_mmio};
}  // namespace

HostLink& host_link() { return g_link; }

}  // namespace palp::stm32::link_uart

// vectors.cpp declares the weak default inside extern "C"; without the same linkage here this
// would be a different (mangled) symbol and the vector table would keep the default handler.
extern "C" void LPUART_IRQHandler();
extern "C" void LPUART_IRQHandler() { palp::stm32::link_uart::host_link().on_irq(); }
