// The STM32G474 board's control-tick interrupt: ADC1's end of the injected sequence (ADC1_2,
// IRQ 18, vectors_list.hpp) runs the app's tick through the board (stm_board.hpp on_tick_irq).
// The strong definition replaces vectors.cpp's weak default of the same name; StmBoard's
// constructor calls set_tick_irq_board(), which pulls this object out of the static library (a
// weak definition alone would not). The link's interrupt (LPUART_IRQHandler) is lpuart1_irq.cpp's.
#include "stm_board.hpp"

namespace palp::stm32 {
namespace {
StmBoard* g_tick_board = nullptr;
}  // namespace

void set_tick_irq_board(StmBoard* board) { g_tick_board = board; }

}  // namespace palp::stm32

// vectors.cpp declares the weak default inside extern "C"; without the same linkage here this
// would be a different (mangled) symbol and the vector table would keep the default handler.
extern "C" void ADC1_2_IRQHandler();
extern "C" void ADC1_2_IRQHandler() { palp::stm32::g_tick_board->on_tick_irq(); }
