// SPDX-License-Identifier: Apache-2.0
// The host link over LPUART1 (firmware/board/stm32g474/link_uart.hpp) on a host register file:
// the baud rate is COMPUTED from the registers written (LPUART: baud = 256 x f_ck / BRR with
// f_ck = the LPUART1SEL clock / PRESC, RM0440's formula restated here), the frame format read
// back from the bits, and the ISR, link read and link write driven against a small model of the
// UART's hardware side (bytes waiting in the RX FIFO, TX FIFO room, the ORE flag).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <deque>
#include <vector>

#include "link_uart.hpp"
#include "register_file.hpp"

namespace palp::stm32::link_uart_test {
namespace {

using test::RegisterFile;
namespace u = lpuart1;

std::uint32_t field(const RegisterFile& rf, const Register& reg, const Field& f) {
  return f.decode(rf.peek(reg));
}

// ---- init: what the registers say -------------------------------------------------------------

double baud_from_registers(const RegisterFile& rf) {
  // LPUART1SEL 00 = PCLK (170 MHz with APB1 /1); the others are not used by the board.
  EXPECT_EQ(field(rf, rcc::Ccipr::reg, rcc::Ccipr::LPUART1SEL), 0u);
  constexpr std::uint32_t kPrescDivider[] = {1, 2, 4, 6, 8, 10, 12, 16, 32, 64, 128, 256};
  const std::uint32_t presc = field(rf, u::Presc::reg, u::Presc::PRESCALER);
  const double f_ck = 170e6 / kPrescDivider[presc < 12 ? presc : 11];
  const double brr = field(rf, u::Brr::reg, u::Brr::BRR);
  return 256.0 * f_ck / brr;
}

TEST(Stm32LinkUart, BaudComputedFromTheRegistersIs921600WithinATenthOfAPercent) {
  RegisterFile rf;
  link_uart::init(rf);
  const double baud = baud_from_registers(rf);
  // UART receivers tolerate a few percent of total mismatch; 0.1 % leaves it all to the host side.
  EXPECT_LT(std::abs(baud - 921600.0) / 921600.0, 1e-3) << baud;
  // LPUART validity: 3 x baud <= f_ck <= 4096 x baud and BRR >= 0x300.
  EXPECT_LE(3.0 * baud, 170e6);
  EXPECT_GE(4096.0 * baud, 170e6);
  EXPECT_GE(field(rf, u::Brr::reg, u::Brr::BRR), 0x300u);
  EXPECT_EQ(field(rf, rcc::Apb1enr2::reg, rcc::Apb1enr2::LPUART1EN), 1u);
  // What the board advertises at baud / 10 bytes per second, 24-byte samples.
  EXPECT_EQ(link_uart::kStreamRateHz, 3840u);
}

TEST(Stm32LinkUart, FrameIs8N1WithFifoOverrunDetectionAndTheRxInterruptOn) {
  RegisterFile rf;
  link_uart::init(rf);
  EXPECT_EQ(field(rf, u::Cr1::reg, u::Cr1::M1), 0u);  // M1:M0 = 00: 8 data bits
  EXPECT_EQ(field(rf, u::Cr1::reg, u::Cr1::M0), 0u);
  EXPECT_EQ(field(rf, u::Cr1::reg, u::Cr1::PCE), 0u);  // no parity
  EXPECT_EQ(field(rf, u::Cr2::reg, u::Cr2::STOP), 0u);  // 1 stop bit
  EXPECT_EQ(field(rf, u::Cr1::reg, u::Cr1::FIFOEN), 1u);
  EXPECT_EQ(field(rf, u::Cr3::reg, u::Cr3::OVRDIS), 0u);
  EXPECT_EQ(field(rf, u::Cr1::reg, u::Cr1::RXNEIE), 1u);
  EXPECT_EQ(field(rf, u::Cr1::reg, u::Cr1::TXEIE), 0u);
}

TEST(Stm32LinkUart, UeIsWrittenLastAloneAfterTeReAndEveryConfigurationRegister) {
  RegisterFile rf;
  link_uart::init(rf);
  const auto& log = rf.log();
  ASSERT_FALSE(log.empty());
  // The last write sets UE; no earlier write to CR1 had UE; BRR/PRESC/CR2/CR3 come before.
  const Write last = log.back();
  EXPECT_EQ(last.address, u::Cr1::reg.address());
  EXPECT_EQ(u::Cr1::UE.decode(last.value), 1u);
  bool te_re_before_ue = false;
  for (std::size_t i = 0; i + 1 < log.size(); ++i) {
    if (log[i].address == u::Cr1::reg.address()) {
      EXPECT_EQ(u::Cr1::UE.decode(log[i].value), 0u) << "write " << i;
      te_re_before_ue = te_re_before_ue ||
                        (u::Cr1::TE.decode(log[i].value) && u::Cr1::RE.decode(log[i].value));
    }
  }
  EXPECT_TRUE(te_re_before_ue);
  const auto index_of = [&](const Register& reg) {
    for (std::size_t i = 0; i < log.size(); ++i)
      if (log[i].address == reg.address()) return i;
    return log.size();
  };
  for (const Register* reg : {&u::Brr::reg, &u::Presc::reg, &u::Cr2::reg, &u::Cr3::reg}) {
    EXPECT_LT(index_of(*reg), log.size() - 1) << reg->name;
  }
}

// ---- the link: ISR, read, write against a model of the UART ------------------------------------

/// The register file plus the UART's hardware side: bytes waiting (RX FIFO + wire), TX FIFO room,
/// ORE cleared by ICR.ORECF. ISR.RXNE / TXE follow the model on every read.
class UartModel {
 public:
  std::uint32_t read(std::uint32_t address) {
    if (address == u::Isr::reg.address()) {
      std::uint32_t isr = rf.peek(u::Isr::reg) & u::Isr::ORE.mask();
      if (!waiting.empty()) isr |= u::Isr::RXNE.mask();
      if (tx_room > 0) isr |= u::Isr::TXE.mask();
      return isr;
    }
    if (address == u::Rdr::reg.address()) {
      if (waiting.empty()) return 0;
      const std::uint8_t b = waiting.front();
      waiting.pop_front();
      return b;
    }
    return rf.read(address);
  }
  void write(std::uint32_t address, std::uint32_t value) {
    if (address == u::Icr::reg.address()) {
      rf.poke(u::Isr::reg, rf.peek(u::Isr::reg) & ~(value & u::Isr::ORE.mask()));
      return;
    }
    if (address == u::Tdr::reg.address()) {
      ++tdr_writes;
      if (tx_room > 0) {
        --tx_room;
        sent.push_back(static_cast<std::uint8_t>(value));
      } else {
        ++tdr_writes_without_room;
      }
      return;
    }
    rf.write(address, value);
  }
  bool rx_interrupt_enabled() const { return u::Cr1::RXNEIE.decode(rf.peek(u::Cr1::reg)) != 0; }
  void raise_overrun() { rf.poke(u::Isr::reg, rf.peek(u::Isr::reg) | u::Isr::ORE.mask()); }

  RegisterFile rf;
  std::deque<std::uint8_t> waiting;
  std::uint32_t tx_room = 0;
  std::vector<std::uint8_t> sent;
  int tdr_writes = 0;
  int tdr_writes_without_room = 0;
};
static_assert(RegisterAccess<UartModel>);

constexpr std::size_t kRing = 8;
using TestLink = link_uart::Link<UartModel, kRing>;

std::vector<std::uint8_t> read_all(TestLink& link) {
  std::vector<std::uint8_t> out(64);
  out.resize(link.read_bytes(out.data(), out.size()));
  return out;
}

TEST(Stm32LinkUart, IsrDrainsTheRxFifoAndLinkReadReturnsTheBytesInOrder) {
  UartModel hw;
  link_uart::init(hw);
  TestLink link(hw);
  hw.waiting = {0x10, 0x20, 0x30};
  link.on_irq();
  EXPECT_TRUE(hw.waiting.empty());
  EXPECT_EQ(read_all(link), (std::vector<std::uint8_t>{0x10, 0x20, 0x30}));
  EXPECT_EQ(read_all(link), std::vector<std::uint8_t>{});
}

TEST(Stm32LinkUart, AFullRingMasksTheRxInterruptLeavesBytesInHardwareAndReadResumesLosingNone) {
  UartModel hw;
  link_uart::init(hw);
  TestLink link(hw);
  std::vector<std::uint8_t> expected;
  for (std::uint8_t b = 0; b < kRing + 3; ++b) {
    hw.waiting.push_back(b);
    expected.push_back(b);
  }
  link.on_irq();
  EXPECT_TRUE(link.rx_paused());
  EXPECT_FALSE(hw.rx_interrupt_enabled());
  EXPECT_EQ(hw.waiting.size(), 3u);  // held by the hardware, not dropped
  std::vector<std::uint8_t> got = read_all(link);
  EXPECT_FALSE(link.rx_paused());
  EXPECT_TRUE(hw.rx_interrupt_enabled());  // RXFNE still set: the interrupt fires again
  link.on_irq();
  const std::vector<std::uint8_t> rest = read_all(link);
  got.insert(got.end(), rest.begin(), rest.end());
  EXPECT_EQ(got, expected);
  EXPECT_EQ(link.overruns(), 0u);
}

TEST(Stm32LinkUart, OverrunIsCountedAndClearedSoTheInterruptDoesNotRepeat) {
  UartModel hw;
  link_uart::init(hw);
  TestLink link(hw);
  hw.raise_overrun();
  hw.waiting = {0x55};
  link.on_irq();
  EXPECT_EQ(link.overruns(), 1u);
  EXPECT_EQ(u::Isr::ORE.decode(hw.read(u::Isr::reg.address())), 0u);
  link.on_irq();  // nothing new: the count stays
  EXPECT_EQ(link.overruns(), 1u);
  EXPECT_EQ(read_all(link), std::vector<std::uint8_t>{0x55});
}

TEST(Stm32LinkUart, LinkWriteFillsTdrOnlyWhileTheTxFifoHasRoomAndNeverBlocks) {
  UartModel hw;
  link_uart::init(hw);
  TestLink link(hw);
  const std::uint8_t msg[] = {1, 2, 3, 4, 5};
  hw.tx_room = 0;
  EXPECT_EQ(link.write_bytes(msg, sizeof msg), 0u);  // busy: returns at once
  hw.tx_room = 3;
  EXPECT_EQ(link.write_bytes(msg, sizeof msg), 3u);
  hw.tx_room = 8;
  EXPECT_EQ(link.write_bytes(msg + 3, 2), 2u);
  EXPECT_EQ(hw.sent, (std::vector<std::uint8_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(hw.tdr_writes_without_room, 0);
  EXPECT_EQ(hw.tdr_writes, 5);
}

}  // namespace
}  // namespace palp::stm32::link_uart_test
