// SPDX-License-Identifier: Apache-2.0
// The host link of the STM32G474 board until USB exists: LPUART1 to the NUCLEO's ST-LINK virtual
// COM port (PA2 TX / PA3 RX, AF12; the host opens `serial:///dev/ttyACM0?baud=921600`).
// Written against the register seam (regs/register.hpp) like clock.hpp, so tests/stm32 runs it on
// a host register file. What it does, the QEMU board's link as the model (board.hpp link_read /
// link_write):
//   init     PCLK (170 MHz) as the kernel clock, PRESC /1, BRR = 256 x f_ck / baud, 8N1, FIFO
//            mode, overrun detection on, RX interrupt on; UE written last, alone.
//   on_irq   (LPUART_IRQHandler) drains the RX FIFO into a fixed SpscQueue; a full ring masks
//            the RX interrupt and leaves the bytes in the hardware; an overrun (ORE) is counted
//            and cleared, never silent.
//   read     pops the ring; if the ISR had masked itself, the interrupt is re-enabled once there
//            is room (the still-set RXFNE then raises it at once: the line is level-sensitive).
//   write    non-blocking: TDR written only while ISR.TXFNF says the TX FIFO has room; when it
//            could not take everything the board arms the TX-FIFO-not-full interrupt
//            (arm_tx_wakeup: CR1.TXFNFIE, the SVD's TXEIE), which on_irq disarms as soon as the
//            FIFO has room again, so the main loop's WFI wakes to write the rest.
// CR1 is read-modify-written by the ISR (it only ever CLEARS an enable: RXNEIE when the ring is
// full, TXEIE when the FIFO has room) and by the main loop (it only SETS one: RXNEIE on resume,
// TXEIE to arm). An ISR's clear lost to a main-loop write in flight re-sets that enable, whose
// condition still holds: the interrupt comes once more and the ISR clears it again. Nothing is
// lost either way; the board still arms under its interrupt lock.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>

#include "clock.hpp"
#include "palp/fw/spsc_queue.hpp"
#include "regs/rcc.hpp"
#include "regs/usart.hpp"

namespace palp::stm32::link_uart {

/// 921600 baud: the fastest standard rate every host serial stack accepts; the facts sheet does
/// not give the ST-LINK V3E VCP's maximum (to confirm on the bench before going higher).
inline constexpr std::uint32_t kBaud = 921'600;
/// LPUART1's kernel clock: PCLK1 = 170 MHz (APB1 /1, facts §3.2), LPUART1SEL = PCLK, PRESC /1.
inline constexpr std::uint32_t kKernelClockHz = clock::kSysclkHz;
inline constexpr std::uint32_t kPrescaler = 0;  // PRESC 0000 = /1

/// LPUART's divider, rounded to nearest: BRR = 256 x f_ck / baud.
constexpr std::uint32_t brr_for(std::uint32_t f_ck_hz, std::uint32_t baud) {
  return static_cast<std::uint32_t>((256ull * f_ck_hz + baud / 2) / baud);
}
inline constexpr std::uint32_t kBrr = brr_for(kKernelClockHz, kBaud);
// LPUART constraints (RM0440 LPUART baud-rate section): 3 x baud <= f_ck <= 4096 x baud, and BRR
// >= 0x300 and within the 20-bit field (SVD).
static_assert(3ull * kBaud <= kKernelClockHz && kKernelClockHz <= 4096ull * kBaud);
static_assert(kBrr >= 0x300 && kBrr < (1u << 20));

/// What the board advertises: the SDK's serial transport budgets baud / 10 bytes per second, and a
/// sample of all 11 channels is 24 bytes: 92160 B/s / 24 B = 3840 samples per second.
inline constexpr std::uint32_t kLinkBytesPerSecond = kBaud / 10;
inline constexpr std::uint32_t kSampleBytes = 24;
inline constexpr std::uint32_t kStreamRateHz = kLinkBytesPerSecond / kSampleBytes;
static_assert(kStreamRateHz == 3840);

/// Clock, pins' peripheral side and frame format; the GPIO alternate function (PA2/PA3 AF12) is
/// the board's pin setup. Leaves the link enabled with the RX interrupt on (the NVIC line
/// LPUART = IRQ 91 is the board's to enable).
template <RegisterAccess A>
void init(A& io) {
  write_field(io, rcc::Apb1enr2::reg, rcc::Apb1enr2::LPUART1EN, 1);
  write_field(io, rcc::Ccipr::reg, rcc::Ccipr::LPUART1SEL,
              rcc::Ccipr::kLpuart1Pclk);
  io.write(lpuart1::Cr1::reg.address(), 0);  // UE = 0: the configuration registers are writable
  io.write(lpuart1::Presc::reg.address(), lpuart1::Presc::PRESCALER.encode(kPrescaler));
  io.write(lpuart1::Brr::reg.address(), lpuart1::Brr::BRR.encode(kBrr));
  io.write(lpuart1::Cr2::reg.address(), lpuart1::Cr2::STOP.encode(0));  // 1 stop bit
  io.write(lpuart1::Cr3::reg.address(), 0);  // OVRDIS = 0: overruns raise ORE
  using C = lpuart1::Cr1;                    // M1:M0 = 00 (8 bits), PCE = 0 (no parity)
  const std::uint32_t cr1 = C::FIFOEN.mask() | C::RXNEIE.mask() | C::TE.mask() | C::RE.mask();
  io.write(C::reg.address(), cr1);
  io.write(C::reg.address(), cr1 | C::UE.mask());
}

/// The link's state: the RX ring the ISR fills and the main loop drains, and the overrun count.
template <RegisterAccess A, std::size_t RingBytes>
class Link {
 public:
  constexpr explicit Link(A& io) : io_(io) {}

  /// LPUART_IRQHandler's body.
  void on_irq() {
    std::uint32_t isr = read(io_, lpuart1::Isr::reg);
    if (lpuart1::Isr::TXE.decode(isr) != 0 &&
        read_field(io_, lpuart1::Cr1::reg, lpuart1::Cr1::TXEIE) != 0) {  // room again: disarm
      write_field(io_, lpuart1::Cr1::reg, lpuart1::Cr1::TXEIE, 0);
    }
    if (lpuart1::Isr::ORE.decode(isr) != 0) {  // a byte was lost on the wire: count, clear
      overruns_.store(overruns_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
      io_.write(lpuart1::Icr::reg.address(), lpuart1::Icr::ORECF.mask());
    }
    while (lpuart1::Isr::RXNE.decode(isr) != 0) {
      if (rx_.full()) {  // leave the bytes in the FIFO; read() re-enables the interrupt
        write_field(io_, lpuart1::Cr1::reg, lpuart1::Cr1::RXNEIE, 0);
        rx_paused_.store(true, std::memory_order_release);
        return;
      }
      rx_.push(static_cast<std::uint8_t>(read_field(io_, lpuart1::Rdr::reg, lpuart1::Rdr::RDR)));
      isr = read(io_, lpuart1::Isr::reg);
    }
  }

  /// board.hpp link_read: up to `size` received bytes, oldest first.
  std::size_t read_bytes(std::uint8_t* bytes, std::size_t size) {
    std::size_t n = 0;
    while (n < size && rx_.pop(bytes[n])) ++n;
    // The ISR is masked while paused, so this read-modify-write of CR1 cannot race it.
    if (rx_paused_.load(std::memory_order_acquire) && !rx_.full()) {
      rx_paused_.store(false, std::memory_order_relaxed);
      write_field(io_, lpuart1::Cr1::reg, lpuart1::Cr1::RXNEIE, 1);
    }
    return n;
  }

  /// board.hpp link_write: as many bytes as the TX FIFO takes now (0: busy; call again later).
  std::size_t write_bytes(const std::uint8_t* bytes, std::size_t size) {
    std::size_t n = 0;
    while (n < size && read_field(io_, lpuart1::Isr::reg, lpuart1::Isr::TXE) != 0) {
      io_.write(lpuart1::Tdr::reg.address(), lpuart1::Tdr::TDR.encode(bytes[n++]));
    }
    return n;
  }

  /// Arms the TX-FIFO-not-full interrupt (after write_bytes took less than asked): on_irq
  /// disarms it once the FIFO has room, which wakes the main loop.
  void arm_tx_wakeup() { write_field(io_, lpuart1::Cr1::reg, lpuart1::Cr1::TXEIE, 1); }
  bool tx_wakeup_armed() { return read_field(io_, lpuart1::Cr1::reg, lpuart1::Cr1::TXEIE) != 0; }

  /// Overruns since start (each lost at least one byte): for a health field.
  std::uint32_t overruns() const { return overruns_.load(std::memory_order_relaxed); }
  /// True while the ring is full and the RX interrupt masked.
  bool rx_paused() const { return rx_paused_.load(std::memory_order_relaxed); }
  std::size_t rx_pending() const { return rx_.size(); }

 private:
  A& io_;
  fw::SpscQueue<std::uint8_t, RingBytes> rx_;
  std::atomic<bool> rx_paused_{false};
  std::atomic<std::uint32_t> overruns_{0};
};

/// The target's link: 512 received bytes of room (a few command frames) on the memory-mapped
/// LPUART1. Defined in lpuart1_irq.cpp, whose LPUART_IRQHandler (the vector table's IRQ 91 entry,
/// vectors_list.hpp spells it `LPUART`) calls on_irq(); using host_link() links the handler in.
inline constexpr std::size_t kRxRingBytes = 512;
using HostLink = Link<Mmio, kRxRingBytes>;
HostLink& host_link();

}  // namespace palp::stm32::link_uart
