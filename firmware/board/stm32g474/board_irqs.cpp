// SPDX-License-Identifier: Apache-2.0
// The STM32G474 board's interrupts that reach the board object: the control tick, ADC1's end of
// the injected sequence (ADC1_2, IRQ 18, vectors_list.hpp), runs the app's tick (stm_board.hpp
// on_tick_irq); USB_LP (IRQ 20) services the USB device (on_usb_irq). The strong definitions
// replace vectors.cpp's weak defaults of the same names; StmBoard's constructor calls
// set_irq_board(), which pulls this object out of the static library (a weak definition alone
// would not). The LPUART1 link's interrupt (LPUART_IRQHandler) is lpuart1_irq.cpp's.
#include "stm_board.hpp"

namespace palp::stm32 {
namespace {
StmBoard* g_board = nullptr;
}  // namespace

void set_irq_board(StmBoard* board) { g_board = board; }

}  // namespace palp::stm32

// vectors.cpp declares the weak defaults inside extern "C"; without the same linkage here these
// would be different (mangled) symbols and the vector table would keep the default handlers.
extern "C" void ADC1_2_IRQHandler();
extern "C" void ADC1_2_IRQHandler() { palp::stm32::g_board->on_tick_irq(); }
extern "C" void USB_LP_IRQHandler();
extern "C" void USB_LP_IRQHandler() { palp::stm32::g_board->on_usb_irq(); }
