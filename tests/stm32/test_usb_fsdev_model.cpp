// SPDX-License-Identifier: Apache-2.0
// The peripheral model (fsdev_model.hpp) itself, driven by raw register writes and host packets
// (no driver): the write semantics of stm32g474-facts.md §5.2 the driver tests rely on to catch
// a read-modify-write, a flag written 1, a wrong PMA stride.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "fsdev_model.hpp"

namespace palp::stm32::test {
namespace {

using Epr = usb::Epr;

/// A model with the clock on, powered up, attached, EF set and EP1R a bulk endpoint whose
/// descriptor points RX at PMA 0x40 (64 bytes) and TX at 0x80, set by raw writes.
class FsdevModelTest : public ::testing::Test {
 protected:
  void SetUp() override {
    m.write(rcc::Apb1enr1::reg.address(), rcc::Apb1enr1::USBEN.mask());
    m.write(usb::Cntr::reg.address(), 0);
    m.write(usb::Bcdr::reg.address(), usb::Bcdr::DPPU.mask());
    m.write(usb::Daddr::reg.address(), usb::Daddr::EF.mask());
    m.write16(usb::kPmaBase + 8 + FsdevModel::kAddrTx, 0x80);
    m.write16(usb::kPmaBase + 8 + FsdevModel::kAddrRx, 0x40);
    m.write16(usb::kPmaBase + 8 + FsdevModel::kCountRx, 0x8400);  // 64 bytes
    m.write(Epr::address(1), Epr::EA.encode(1));                     // bulk, disabled
  }

  FsdevModel m;
};

TEST_F(FsdevModelTest, StatAndDtogBitsToggleOnAWrittenOneAndStayOnAZero) {
  m.write(Epr::address(1), Epr::EA.encode(1) | Epr::STAT_RX.encode(Epr::kStatValid) |
                               Epr::DTOG_TX.mask());
  EXPECT_EQ(Epr::STAT_RX.decode(m.epr(1)), Epr::kStatValid);
  EXPECT_EQ(Epr::DTOG_TX.decode(m.epr(1)), 1u);
  // Writing back what was read (a read-modify-write) toggles them all back off.
  m.write(Epr::address(1), m.read(Epr::address(1)));
  EXPECT_EQ(Epr::STAT_RX.decode(m.epr(1)), Epr::kStatDisabled);
  EXPECT_EQ(Epr::DTOG_TX.decode(m.epr(1)), 0u);
  m.write(Epr::address(1), Epr::EA.encode(1) | Epr::STAT_TX.encode(Epr::kStatNak));
  m.write(Epr::address(1), Epr::EA.encode(1) | Epr::STAT_TX.encode(0b01));  // 10 ^ 01 = 11
  EXPECT_EQ(Epr::STAT_TX.decode(m.epr(1)), Epr::kStatValid);
}

TEST_F(FsdevModelTest, CtrBitsClearOnAWrittenZeroAndCannotBeSetBySoftware) {
  m.write(Epr::address(1), Epr::EA.encode(1) | Epr::CTR_RX.mask() | Epr::CTR_TX.mask());
  EXPECT_EQ(m.epr(1) & (Epr::CTR_RX.mask() | Epr::CTR_TX.mask()), 0u);
  m.write(Epr::address(1), Epr::EA.encode(1) | Epr::STAT_RX.encode(Epr::kStatValid) |
                               Epr::STAT_TX.encode(Epr::kStatValid));
  const std::array<std::uint8_t, 3> bytes = {1, 2, 3};
  ASSERT_EQ(m.out(1, bytes), Handshake::ack);
  ASSERT_EQ(m.in(1).handshake, Handshake::ack);
  EXPECT_EQ(m.istr() & (usb::Istr::CTR.mask() | usb::Istr::DIR.mask() | usb::Istr::EP_ID.mask()),
            usb::Istr::CTR.mask() | usb::Istr::DIR.mask() | 1u);
  m.write(Epr::address(1), Epr::EA.encode(1) | Epr::CTR_TX.mask());  // CTR_RX 0: cleared
  EXPECT_EQ(m.epr(1) & Epr::CTR_RX.mask(), 0u);
  EXPECT_NE(m.epr(1) & Epr::CTR_TX.mask(), 0u);
  EXPECT_EQ(m.istr() & (usb::Istr::CTR.mask() | usb::Istr::DIR.mask()), usb::Istr::CTR.mask());
  m.write(Epr::address(1), Epr::EA.encode(1));
  EXPECT_EQ(m.istr() & usb::Istr::CTR.mask(), 0u);
}

TEST_F(FsdevModelTest, AReceivedPacketSetsCountCtrAndNakAndTogglesDtogRx) {
  m.write(Epr::address(1), Epr::EA.encode(1) | Epr::STAT_RX.encode(Epr::kStatValid));
  const std::vector<std::uint8_t> bytes = {9, 8, 7, 6, 5};
  ASSERT_EQ(m.out(1, bytes), Handshake::ack);
  EXPECT_EQ(m.descriptor(1, FsdevModel::kCountRx), 0x8400 | 5);
  EXPECT_EQ(m.pma16(0x40), 0x0809);  // little-endian halfwords, 1:1 byte offsets
  EXPECT_EQ(m.pma16(0x44), 0x0005);
  EXPECT_EQ(Epr::STAT_RX.decode(m.epr(1)), Epr::kStatNak);
  EXPECT_EQ(Epr::DTOG_RX.decode(m.epr(1)), 1u);
  EXPECT_EQ(m.out(1, bytes), Handshake::nak);
}

TEST_F(FsdevModelTest, AnOutLargerThanTheAllocationIsNotAcknowledged) {
  m.write16(usb::kPmaBase + 8 + FsdevModel::kCountRx, 0x1000);  // BL_SIZE 0, 4 blocks: 8 bytes
  EXPECT_EQ(m.rx_allocation(1), 8u);
  m.write(Epr::address(1), Epr::EA.encode(1) | Epr::STAT_RX.encode(Epr::kStatValid));
  EXPECT_EQ(m.out(1, std::vector<std::uint8_t>(9)), Handshake::none);
  EXPECT_EQ(m.rx_overflows(), 1u);
  EXPECT_EQ(m.out(1, std::vector<std::uint8_t>(8)), Handshake::ack);
}

TEST_F(FsdevModelTest, RxAllocationDecodesBothBlockSizes) {
  const std::array<std::pair<std::uint16_t, std::uint16_t>, 5> cases = {
      {{0x8400, 64}, {0x8000, 32}, {0x7C00, 62}, {0x0400, 2}, {0x0000, 0}}};
  for (const auto& [encoded, bytes] : cases) {
    m.write16(usb::kPmaBase + 8 + FsdevModel::kCountRx, encoded);
    EXPECT_EQ(m.rx_allocation(1), bytes) << std::hex << encoded;
  }
}

TEST_F(FsdevModelTest, IstrFlagsClearOnlyWhereZeroIsWritten) {
  m.bus_reset();
  m.suspend();
  const std::uint32_t both = usb::Istr::RESET.mask() | usb::Istr::SUSP.mask();
  EXPECT_EQ(m.istr(), both);
  m.write(usb::Istr::reg.address(), usb::Istr::RESET.mask());  // 1 in RESET, 0 elsewhere
  EXPECT_EQ(m.istr(), usb::Istr::RESET.mask());
  m.write(usb::Istr::reg.address(), 0xFFFF);  // software cannot set a flag
  EXPECT_EQ(m.istr(), usb::Istr::RESET.mask());
  m.write(usb::Istr::reg.address(), ~usb::Istr::RESET.mask() & 0xFFFF);
  EXPECT_EQ(m.istr(), 0u);
}

TEST_F(FsdevModelTest, ABusResetDisablesEveryEndpointAndTheAddress) {
  m.write(Epr::address(1), Epr::EA.encode(1) | Epr::STAT_TX.encode(Epr::kStatNak));
  m.write(usb::Daddr::reg.address(), usb::Daddr::EF.mask() | 5);
  m.bus_reset();
  EXPECT_EQ(m.epr(1), 0u);
  EXPECT_EQ(m.daddr(), 0u);
  EXPECT_EQ(m.in(1).handshake, Handshake::none);
}

TEST_F(FsdevModelTest, ThePmaTakesHalfwordsAtEvenOffsetsOnly) {
  m.write(usb::kPmaBase + 0x100, 0x12345678);
  EXPECT_EQ(m.faults().pma_wide, 1u);
  EXPECT_EQ(m.pma16(0x100), 0u);
  m.write16(usb::kPmaBase + 0x101, 0xAAAA);
  EXPECT_EQ(m.faults().pma_misaligned, 1u);
  m.write16(usb::kPmaBase + usb::kPmaSize, 0xAAAA);
  EXPECT_EQ(m.faults().pma_misaligned, 2u);
  m.write16(usb::kPmaBase + 0x3FE, 0xBEEF);
  EXPECT_EQ(m.read16(usb::kPmaBase + 0x3FE), 0xBEEF);
}

TEST(FsdevModel, UsbAccessesWithoutTheClockAreIgnoredAndCounted) {
  FsdevModel m;
  m.write(usb::Cntr::reg.address(), 0);
  m.write16(usb::kPmaBase, 1);
  EXPECT_EQ(m.faults().without_clock, 2u);
  EXPECT_EQ(m.cntr(), usb::Cntr::FRES.mask() | usb::Cntr::PDWN.mask());  // reset value kept
}

TEST_F(FsdevModelTest, TheDeviceAnswersOnlyWhenPoweredAttachedEnabledAndAddressed) {
  m.write(Epr::address(1), Epr::EA.encode(1) | Epr::STAT_TX.encode(Epr::kStatNak));
  EXPECT_EQ(m.in(1).handshake, Handshake::nak);
  m.write(usb::Bcdr::reg.address(), 0);
  EXPECT_EQ(m.in(1).handshake, Handshake::none);
  m.write(usb::Bcdr::reg.address(), usb::Bcdr::DPPU.mask());
  m.write(usb::Cntr::reg.address(), usb::Cntr::FRES.mask());
  EXPECT_EQ(m.in(1).handshake, Handshake::none);
  m.write(usb::Cntr::reg.address(), 0);
  m.write(usb::Daddr::reg.address(), 3);  // EF off
  EXPECT_EQ(m.in(1).handshake, Handshake::none);
  m.write(usb::Daddr::reg.address(), usb::Daddr::EF.mask() | 3);
  EXPECT_EQ(m.in(1).handshake, Handshake::none);  // the host still talks to 0
  m.set_host_address(3);
  EXPECT_EQ(m.in(1).handshake, Handshake::nak);
}

}  // namespace
}  // namespace palp::stm32::test
