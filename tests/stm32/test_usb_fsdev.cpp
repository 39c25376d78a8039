// SPDX-License-Identifier: Apache-2.0
// The FSDEV driver (firmware/board/stm32g474/usb_fsdev.hpp) against the peripheral model
// (fsdev_model.hpp): init state, SETUP/OUT/IN packets through the PMA, NAK and STALL, the
// rc_w0 and toggle bits never clobbered, the address, bus reset, suspend/resume, refusals.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "test_usb_fsdev_fixture.hpp"

namespace palp::stm32::test {
namespace {

using Epr = usb::Epr;
using Lines = std::vector<std::string>;

constexpr std::array<std::uint8_t, 8> kGetDeviceDescriptor = {0x80, 0x06, 0x00, 0x01,
                                                              0x00, 0x00, 0x40, 0x00};

std::uint32_t stat_rx(const FsdevModel& m, std::uint8_t n) { return Epr::STAT_RX.decode(m.epr(n)); }
std::uint32_t stat_tx(const FsdevModel& m, std::uint8_t n) { return Epr::STAT_TX.decode(m.epr(n)); }

TEST(UsbFsdevInit, EnablesTheClockFirstAndPowersUpInTheFactsSheetOrder) {
  FsdevModel model;
  UsbFsdev<FsdevModel> driver{model};
  driver.init();
  EXPECT_EQ(model.faults().without_clock, 0u);  // no USB access before RCC_APB1ENR1.USBEN
  // CNTR writes (facts §5.3 item 1): FRES|PDWN, FRES, (t_STARTUP), 0, then the interrupt masks.
  std::vector<FsdevModel::Write> cntr;
  std::size_t istr_clear = 0;
  for (std::size_t i = 0; i < model.log().size(); ++i) {
    const FsdevModel::Write& w = model.log()[i];
    if (w.address == usb::Cntr::reg.address()) {
      cntr.push_back(w);
    } else if (w.address == usb::Istr::reg.address() && w.value == 0 && istr_clear == 0) {
      istr_clear = i;
    }
  }
  ASSERT_EQ(cntr.size(), 4u);
  EXPECT_EQ(cntr[0].value, usb::Cntr::FRES.mask() | usb::Cntr::PDWN.mask());
  EXPECT_EQ(cntr[1].value, usb::Cntr::FRES.mask());
  EXPECT_EQ(cntr[2].value, 0u);
  // ≥ 1 µs between PDWN off and FRES off: at least 170 reads (one 170 MHz cycle each at least).
  EXPECT_GE(cntr[2].reads_before - cntr[1].reads_before, 170u);
  EXPECT_EQ(cntr[3].value, usb::Cntr::CTRM.mask() | usb::Cntr::RESETM.mask() |
                               usb::Cntr::SUSPM.mask() | usb::Cntr::WKUPM.mask());
  EXPECT_GT(istr_clear, 0u);
  EXPECT_EQ(model.cntr(), cntr[3].value);
}

TEST(UsbFsdevInit, LeavesTheStatedPmaLayoutEndpointsAddressAndNoPullUp) {
  FsdevModel model;
  UsbFsdev<FsdevModel> driver{model};
  driver.init();
  EXPECT_EQ(model.btable(), 0u);
  // The layout table of usb_fsdev.hpp, restated: {ADDR_TX, ADDR_RX} per EPnR 0..2, 64 bytes each.
  constexpr std::uint16_t kTx[] = {0x080, 0x100, 0x180};
  constexpr std::uint16_t kRx[] = {0x040, 0x0C0, 0x140};
  for (std::uint8_t n = 0; n < 3; ++n) {
    EXPECT_EQ(model.descriptor(n, FsdevModel::kAddrTx), kTx[n]) << "EP" << int(n);
    EXPECT_EQ(model.descriptor(n, FsdevModel::kAddrRx), kRx[n]) << "EP" << int(n);
    EXPECT_EQ(model.rx_allocation(n), 64u) << "EP" << int(n);
  }
  EXPECT_EQ(Epr::EP_TYPE.decode(model.epr(0)), Epr::kTypeControl);
  EXPECT_EQ(Epr::EA.decode(model.epr(0)), 0u);
  EXPECT_EQ(stat_rx(model, 0), Epr::kStatValid);  // ready for the first SETUP
  EXPECT_EQ(stat_tx(model, 0), Epr::kStatNak);
  EXPECT_EQ(model.epr(0) & (Epr::DTOG_RX.mask() | Epr::DTOG_TX.mask()), 0u);
  for (std::uint8_t n = 1; n < 8; ++n) {
    EXPECT_EQ(stat_rx(model, n), Epr::kStatDisabled) << "EP" << int(n);
    EXPECT_EQ(stat_tx(model, n), Epr::kStatDisabled) << "EP" << int(n);
  }
  EXPECT_EQ(model.daddr(), usb::Daddr::EF.mask());
  EXPECT_FALSE(model.attached());
  driver.connect(true);
  EXPECT_TRUE(model.attached());
  driver.connect(false);
  EXPECT_FALSE(model.attached());
  EXPECT_EQ(model.faults().total(), 0u);
}

TEST_F(UsbFsdevTest, ASetupArrivesAsASetupEventWithItsEightBytes) {
  ASSERT_EQ(model.setup(0, kGetDeviceDescriptor), Handshake::ack);
  EXPECT_EQ(drain(), Lines{"setup 0"});
  std::array<std::uint8_t, 64> bytes{};
  ASSERT_EQ(driver.read_out(0, bytes.data(), bytes.size()), 8u);
  EXPECT_TRUE(std::equal(kGetDeviceDescriptor.begin(), kGetDeviceDescriptor.end(), bytes.begin()));
  // Both directions NAK until the core answers; both toggles DATA1 for the data/status stages.
  EXPECT_EQ(stat_rx(model, 0), Epr::kStatNak);
  EXPECT_EQ(stat_tx(model, 0), Epr::kStatNak);
  EXPECT_NE(model.epr(0) & Epr::DTOG_RX.mask(), 0u);
  EXPECT_NE(model.epr(0) & Epr::DTOG_TX.mask(), 0u);
  EXPECT_EQ(model.istr() & usb::Istr::CTR.mask(), 0u);
  // The data stage's first IN is DATA1, the status OUT (zero length) is DATA1.
  driver.write_in(0, bytes.data(), 18);
  EXPECT_EQ(model.in(0).pid_data, 1u);
  EXPECT_EQ(drain(), Lines{"in_complete 0"});
  driver.arm_out(0);
  EXPECT_EQ(model.out(0, {}), Handshake::ack);
  EXPECT_EQ(drain(), Lines{"out 0"});
  EXPECT_EQ(driver.read_out(0, bytes.data(), bytes.size()), 0u);
}

TEST_F(UsbFsdevTest, ASetupOfOtherThanEightBytesIsDroppedAndEp0ReArmed) {
  const std::array<std::uint8_t, 5> damaged = {0x80, 0x06, 0x00, 0x01, 0x00};
  ASSERT_EQ(model.setup(0, damaged), Handshake::ack);
  EXPECT_EQ(drain(), Lines{});
  EXPECT_EQ(stat_rx(model, 0), Epr::kStatValid);
  EXPECT_EQ(model.epr(0) & Epr::CTR_RX.mask(), 0u);
  ASSERT_EQ(model.setup(0, kGetDeviceDescriptor), Handshake::ack);
  EXPECT_EQ(drain(), Lines{"setup 0"});
}

TEST_F(UsbFsdevTest, OutPacketsOfEverySizeFrom0To64AreReadBackExactly) {
  driver.open_endpoint(1, EndpointType::bulk, 64);
  for (std::size_t size = 0; size <= 64; ++size) {
    const std::vector<std::uint8_t> sent = pattern(size, static_cast<unsigned>(size));
    driver.arm_out(1);
    ASSERT_EQ(model.out(1, sent), Handshake::ack) << size;
    ASSERT_EQ(drain(), Lines{"out 1"}) << size;
    std::vector<std::uint8_t> got(64, 0xEE);
    got.resize(driver.read_out(1, got.data(), got.size()));
    EXPECT_EQ(got, sent) << size;
  }
}

TEST_F(UsbFsdevTest, ReadOutCopiesNoMoreThanTheCapacity) {
  driver.open_endpoint(1, EndpointType::bulk, 64);
  driver.arm_out(1);
  const std::vector<std::uint8_t> sent = pattern(64, 3);
  ASSERT_EQ(model.out(1, sent), Handshake::ack);
  std::vector<std::uint8_t> got(8, 0xEE);
  EXPECT_EQ(driver.read_out(1, got.data(), 5), 5u);
  EXPECT_EQ(got, (std::vector<std::uint8_t>{sent[0], sent[1], sent[2], sent[3], sent[4], 0xEE,
                                            0xEE, 0xEE}));
}

TEST_F(UsbFsdevTest, InPacketsOfEverySizeFrom0To64AreTakenExactlyWithAlternatingToggles) {
  driver.open_endpoint(2, EndpointType::interrupt, 64);
  for (std::size_t size = 0; size <= 64; ++size) {
    const std::vector<std::uint8_t> sent = pattern(size, static_cast<unsigned>(size + 1));
    driver.write_in(2, sent.data(), sent.size());
    const InPacket packet = model.in(2);
    ASSERT_EQ(packet.handshake, Handshake::ack) << size;
    EXPECT_EQ(packet.bytes, sent) << size;
    EXPECT_EQ(packet.pid_data, size % 2) << size;  // DATA0 after open, then alternating
    ASSERT_EQ(drain(), Lines{"in_complete 2"}) << size;
  }
}

TEST_F(UsbFsdevTest, AnEndpointNotArmedAnswersNakAndRaisesNoEvent) {
  driver.open_endpoint(1, EndpointType::bulk, 64);
  const std::vector<std::uint8_t> bytes = pattern(10, 0);
  EXPECT_EQ(model.out(1, bytes), Handshake::nak);
  EXPECT_EQ(model.in(1).handshake, Handshake::nak);
  EXPECT_EQ(drain(), Lines{});
  driver.arm_out(1);  // one packet per arm: the next is NAKed until re-armed
  EXPECT_EQ(model.out(1, bytes), Handshake::ack);
  EXPECT_EQ(model.out(1, bytes), Handshake::nak);
  EXPECT_EQ(drain(), Lines{"out 1"});
  // An endpoint never opened does not answer at all.
  EXPECT_EQ(model.in(2).handshake, Handshake::none);
}

TEST_F(UsbFsdevTest, AStalledEndpointAnswersStallUntilReopened) {
  driver.open_endpoint(1, EndpointType::bulk, 64);
  driver.stall(1);
  EXPECT_EQ(model.out(1, pattern(4, 0)), Handshake::stall);
  EXPECT_EQ(model.in(1).handshake, Handshake::stall);
  EXPECT_EQ(drain(), Lines{});
  driver.open_endpoint(1, EndpointType::bulk, 64);  // CLEAR_FEATURE(ENDPOINT_HALT)
  EXPECT_EQ(model.in(1).handshake, Handshake::nak);
  driver.write_in(1, nullptr, 0);
  const InPacket zlp = model.in(1);
  EXPECT_EQ(zlp.handshake, Handshake::ack);
  EXPECT_EQ(zlp.pid_data, 0u);  // toggles back to DATA0
}

TEST_F(UsbFsdevTest, AnEp0StallLastsUntilTheNextSetup) {
  ASSERT_EQ(model.setup(0, kGetDeviceDescriptor), Handshake::ack);
  ASSERT_EQ(drain(), Lines{"setup 0"});
  driver.stall(0);
  EXPECT_EQ(model.in(0).handshake, Handshake::stall);
  EXPECT_EQ(model.out(0, {}), Handshake::stall);
  ASSERT_EQ(model.setup(0, kGetDeviceDescriptor), Handshake::ack);
  EXPECT_EQ(drain(), Lines{"setup 0"});
  EXPECT_EQ(model.in(0).handshake, Handshake::nak);
}

// A bus event between the driver's read of EPnR and its write: an IN taken while poll() acks an
// OUT. The recipe writes CTR_TX = 1 (unchanged) and 0 in every toggle bit, so the new CTR_TX,
// STAT_TX = NAK and the flipped DTOG_TX survive; a read-modify-write would write back what it
// read before the IN (CTR_TX 0: the event lost; STAT/DTOG bits: toggled).
TEST_F(UsbFsdevTest, AckingAnOutDoesNotClearAnInCompletedBetweenReadAndWrite) {
  driver.open_endpoint(1, EndpointType::bulk, 64);
  driver.arm_out(1);
  const std::vector<std::uint8_t> sent = pattern(64, 5);
  driver.write_in(1, sent.data(), sent.size());
  ASSERT_EQ(model.out(1, sent), Handshake::ack);
  InPacket taken;
  model.before_next_write(Epr::address(1), [&] { taken = model.in(1); });
  EXPECT_EQ(describe(driver.poll()), "out 1");
  ASSERT_EQ(taken.handshake, Handshake::ack);
  EXPECT_NE(model.epr(1) & Epr::CTR_TX.mask(), 0u);
  EXPECT_EQ(model.epr(1) & Epr::CTR_RX.mask(), 0u);
  EXPECT_EQ(stat_tx(model, 1), Epr::kStatNak);
  EXPECT_EQ(stat_rx(model, 1), Epr::kStatNak);
  EXPECT_EQ(drain(), Lines{"in_complete 1"});
  // The toggles moved on exactly once each: the next packets are DATA1 both ways.
  driver.arm_out(1);
  EXPECT_EQ(model.out(1, sent), Handshake::ack);
  driver.write_in(1, sent.data(), 1);
  EXPECT_EQ(model.in(1).pid_data, 1u);
  EXPECT_EQ(drain(), (Lines{"in_complete 1", "out 1"}));
}

TEST_F(UsbFsdevTest, AckingAnOutLeavesAQueuedInAndTheOtherToggleBitsAlone) {
  driver.open_endpoint(1, EndpointType::bulk, 64);
  driver.arm_out(1);
  const std::vector<std::uint8_t> sent = pattern(33, 9);
  driver.write_in(1, sent.data(), sent.size());
  const std::uint32_t before = model.epr(1);
  ASSERT_EQ(model.out(1, sent), Handshake::ack);
  EXPECT_EQ(drain(), Lines{"out 1"});
  EXPECT_EQ(stat_tx(model, 1), Epr::kStatValid);  // still queued
  EXPECT_EQ(model.epr(1) & Epr::DTOG_TX.mask(), before & Epr::DTOG_TX.mask());
  EXPECT_EQ(model.in(1).bytes, sent);
  EXPECT_EQ(drain(), Lines{"in_complete 1"});
}

TEST_F(UsbFsdevTest, BothTransferFlagsPendingGiveTwoEventsInBeforeOut) {
  driver.open_endpoint(1, EndpointType::bulk, 64);
  driver.arm_out(1);
  driver.write_in(1, nullptr, 0);
  ASSERT_EQ(model.out(1, pattern(3, 1)), Handshake::ack);
  ASSERT_EQ(model.in(1).handshake, Handshake::ack);
  EXPECT_EQ(drain(), (Lines{"in_complete 1", "out 1"}));
}

TEST_F(UsbFsdevTest, TransfersPendingOnSeveralEndpointsAreEachReportedOnce) {
  driver.open_endpoint(1, EndpointType::bulk, 64);
  driver.open_endpoint(2, EndpointType::interrupt, 64);
  driver.arm_out(1);
  driver.write_in(2, nullptr, 0);
  ASSERT_EQ(model.out(1, pattern(7, 0)), Handshake::ack);
  ASSERT_EQ(model.in(2).handshake, Handshake::ack);
  ASSERT_EQ(model.setup(0, kGetDeviceDescriptor), Handshake::ack);
  EXPECT_EQ(drain(), (Lines{"setup 0", "out 1", "in_complete 2"}));  // EP_ID order
}

// ISTR flags are rc_w0: clearing one by writing its complement leaves the others pending; a
// driver writing the flag itself (1) would clear every other flag and keep the one it meant.
TEST_F(UsbFsdevTest, PendingResetSuspendAndWakeupAreEachReportedOnce) {
  model.bus_reset();
  model.suspend();
  model.resume();
  EXPECT_EQ(drain(), (Lines{"reset 0", "suspend 0", "resume 0"}));
  EXPECT_EQ(model.istr(), 0u);
}

TEST_F(UsbFsdevTest, SuspendSetsFsuspBeforeClearingTheFlagAndWakeupClearsLowPower) {
  model.suspend();
  EXPECT_EQ(drain(), Lines{"suspend 0"});
  EXPECT_NE(model.cntr() & usb::Cntr::FSUSP.mask(), 0u);
  EXPECT_NE(model.cntr() & usb::Cntr::LP_MODE.mask(), 0u);
  EXPECT_EQ(model.suspend_cleared_early(), 0u);
  model.resume();
  EXPECT_EQ(drain(), Lines{"resume 0"});
  EXPECT_EQ(model.cntr() & (usb::Cntr::FSUSP.mask() | usb::Cntr::LP_MODE.mask()), 0u);
  EXPECT_NE(model.cntr() & usb::Cntr::CTRM.mask(), 0u);
}

TEST_F(UsbFsdevTest, TheAddressTakesEffectOnlyWhenSetAndABusResetReturnsToZero) {
  model.set_host_address(9);
  EXPECT_EQ(model.setup(0, kGetDeviceDescriptor), Handshake::none);
  model.set_host_address(0);
  ASSERT_EQ(model.setup(0, kGetDeviceDescriptor), Handshake::ack);  // still at 0
  ASSERT_EQ(drain(), Lines{"setup 0"});
  driver.set_address(9);
  EXPECT_EQ(model.daddr(), usb::Daddr::EF.mask() | 9u);
  EXPECT_EQ(model.setup(0, kGetDeviceDescriptor), Handshake::none);  // the device moved
  model.set_host_address(9);
  EXPECT_EQ(model.setup(0, kGetDeviceDescriptor), Handshake::ack);
  EXPECT_EQ(drain(), Lines{"setup 0"});
  model.bus_reset();
  EXPECT_EQ(drain(), Lines{"reset 0"});
  EXPECT_EQ(model.daddr(), usb::Daddr::EF.mask());
  EXPECT_EQ(model.setup(0, kGetDeviceDescriptor), Handshake::ack);  // host back at 0
}

TEST_F(UsbFsdevTest, ABusResetClosesEveryEndpointButEp0) {
  driver.open_endpoint(1, EndpointType::bulk, 64);
  driver.open_endpoint(2, EndpointType::interrupt, 64);
  model.bus_reset();
  EXPECT_EQ(drain(), Lines{"reset 0"});
  EXPECT_EQ(model.in(1).handshake, Handshake::none);
  EXPECT_EQ(model.out(2, {}), Handshake::none);
  EXPECT_EQ(model.setup(0, kGetDeviceDescriptor), Handshake::ack);
  driver.write_in(1, nullptr, 0);  // closed by the reset: refused
  ++expected_refusals;
  EXPECT_EQ(driver.last_refusal(), fsdev::Refusal::endpoint_closed);
}

TEST_F(UsbFsdevTest, CallsTheLayoutOrStateCannotHonourDoNothingAndSayWhy) {
  const std::uint32_t ep0 = model.epr(0);
  driver.open_endpoint(3, EndpointType::bulk, 64);
  EXPECT_EQ(driver.last_refusal(), fsdev::Refusal::endpoint_out_of_range);
  driver.open_endpoint(1, EndpointType::bulk, 65);
  EXPECT_EQ(driver.last_refusal(), fsdev::Refusal::max_packet_out_of_range);
  driver.arm_out(1);
  EXPECT_EQ(driver.last_refusal(), fsdev::Refusal::endpoint_closed);
  driver.open_endpoint(1, EndpointType::bulk, 32);
  const std::vector<std::uint8_t> bytes = pattern(33, 0);
  driver.write_in(1, bytes.data(), 33);
  EXPECT_EQ(driver.last_refusal(), fsdev::Refusal::packet_too_large);
  driver.write_in(1, bytes.data(), 32);
  driver.write_in(1, bytes.data(), 1);
  EXPECT_EQ(driver.last_refusal(), fsdev::Refusal::in_pending);
  driver.set_address(128);
  EXPECT_EQ(driver.last_refusal(), fsdev::Refusal::address_out_of_range);
  expected_refusals = 6;
  EXPECT_EQ(model.epr(0), ep0);
  EXPECT_EQ(model.daddr(), usb::Daddr::EF.mask());
  EXPECT_EQ(model.in(1).bytes, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 32));
  // A 32-byte endpoint's OUT allocation is 32 bytes (the model refuses a longer packet).
  driver.arm_out(1);
  EXPECT_EQ(model.rx_allocation(1), 32u);
}

}  // namespace
}  // namespace palp::stm32::test
