// SPDX-License-Identifier: Apache-2.0
// CMSDK APB UART registers, the serial port of QEMU's mps2-an386.
//
// Sources:
//   [TRM] ARM Cortex-M System Design Kit Technical Reference Manual, ARM DDI 0479C, chapter 4
//         "APB Components", section "APB UART": programmers model (register offsets and bits).
//   [QD]  reference/qemu-icount.md, "The machine": UART0 base on mps2-an386, the register bits
//         as QEMU implements them (hw/char/cmsdk-apb-uart.c), BAUDDIV >= 16, no FIFO.
//   [AN]  QEMU hw/arm/mps2.c / ARM application note AN386: UART0 at 0x40004000 on the AN386
//         memory map (UART1-4 at 0x40005000/6000/7000/9000); mps2.c wires UART0's receive
//         interrupt to IRQ 0 and its transmit interrupt to IRQ 1 ("RX irq number; TX irq is
//         always one greater", uartirq[] = {0, 2, 4, 18, 20}).
//   [QU]  QEMU hw/char/cmsdk-apb-uart.c: INTSTATUS bit 0 TX, bit 1 RX (write 1 to clear); the RX
//         interrupt is raised when a byte lands in the empty receive buffer, the TX interrupt when
//         TXFULL goes from set to clear; QEMU offers the next received byte only once DATA was
//         read (uart_can_receive), so the receive side never overruns: the host's bytes wait in
//         the chardev while the buffer is full.
#pragma once

#include <cstdint>

namespace palp::board::cmsdk_uart {

inline constexpr std::uintptr_t kUart0Base = 0x40004000u;  // [QD], [AN]
inline constexpr std::uint32_t kUart0RxIrq = 0;             // [AN]
inline constexpr std::uint32_t kUart0TxIrq = 1;             // [AN]

// Register offsets from the UART's base [TRM], [QD]. All registers are 32 bits wide with the
// used bits at the bottom.
inline constexpr std::uintptr_t kData = 0x00;      // DATA: write = transmit, read = received
inline constexpr std::uintptr_t kState = 0x04;     // STATE
inline constexpr std::uintptr_t kCtrl = 0x08;      // CTRL
inline constexpr std::uintptr_t kIntStatus = 0x0C; // INTSTATUS (read) / INTCLEAR (write)
inline constexpr std::uintptr_t kBaudDiv = 0x10;   // BAUDDIV

// INTSTATUS / INTCLEAR bits [TRM], [QU].
inline constexpr std::uint32_t kIntTx = 1u << 0;
inline constexpr std::uint32_t kIntRx = 1u << 1;

// STATE bits [TRM], [QD].
inline constexpr std::uint32_t kStateTxFull = 1u << 0;     // transmit buffer full
inline constexpr std::uint32_t kStateRxFull = 1u << 1;     // receive buffer full
inline constexpr std::uint32_t kStateTxOverrun = 1u << 2;  // write 1 to clear
inline constexpr std::uint32_t kStateRxOverrun = 1u << 3;  // write 1 to clear

// CTRL bits [TRM], [QD].
inline constexpr std::uint32_t kCtrlTxEnable = 1u << 0;
inline constexpr std::uint32_t kCtrlRxEnable = 1u << 1;
inline constexpr std::uint32_t kCtrlTxIrqEnable = 1u << 2;
inline constexpr std::uint32_t kCtrlRxIrqEnable = 1u << 3;

// BAUDDIV: the divider must be at least 16 [TRM], [QD]. QEMU does not model the bit rate, so
// the smallest legal divider is used.
inline constexpr std::uint32_t kMinBaudDiv = 16;

inline volatile std::uint32_t& reg(std::uintptr_t base, std::uintptr_t offset) {
  return *reinterpret_cast<volatile std::uint32_t*>(base + offset);
}

}  // namespace palp::board::cmsdk_uart
