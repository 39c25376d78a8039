// SPDX-License-Identifier: Apache-2.0
// The console: polled transmit on CMSDK UART0 (registers in cmsdk_uart.hpp).
#include "board.hpp"
#include "cmsdk_uart.hpp"

namespace palp::board {

namespace {
using namespace cmsdk_uart;
constexpr std::uintptr_t kConsole = kUart0Base;
}  // namespace

void console_init() {
  reg(kConsole, kCtrl) = 0;  // transmitter off while configuring
  reg(kConsole, kBaudDiv) = kMinBaudDiv;
  reg(kConsole, kState) = kStateTxOverrun | kStateRxOverrun;  // write 1 to clear
  reg(kConsole, kCtrl) = kCtrlTxEnable;
}

void console_write(const char* data, std::size_t size) {
  for (std::size_t k = 0; k < size; ++k) {
    while ((reg(kConsole, kState) & kStateTxFull) != 0) {
    }
    reg(kConsole, kData) = static_cast<unsigned char>(data[k]);
  }
}

}  // namespace palp::board
