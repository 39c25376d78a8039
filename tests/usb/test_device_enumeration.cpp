// SPDX-License-Identifier: Apache-2.0
// The device core's control endpoint (firmware/usb/device.hpp) against a host playing the bus
// (host.hpp, packet_bus.hpp): enumeration as Windows does it (usb-dfu-facts.md §1.10), the ZLP
// rule (§1.11), STALL and its recovery, SET_ADDRESS after the status stage, the standard, HID
// class (§2.2) and MS OS 2.0 (§4.4) requests. Every reply is compared with the bytes
// find_descriptor / ms_os_20_descriptor_set give, never with a copy made here.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "device_rig.hpp"
#include "palp/usb/descriptors.hpp"

namespace palp::usb::test {
namespace {

std::vector<std::uint8_t> bytes_of(std::span<const std::uint8_t> s) { return {s.begin(), s.end()}; }

std::vector<std::uint8_t> first(std::span<const std::uint8_t> s, std::size_t n) {
  return bytes_of(s.first(std::min(n, s.size())));
}

// The data packets a control read of a `reply`-byte answer with wLength `w_length` takes, as
// the ZLP rule of usb-dfu-facts.md §1.11 states it: 64-byte packets, the last one short, and a
// zero-length packet after them when the (truncated) reply is shorter than wLength and a
// non-zero multiple of 64.
std::vector<std::size_t> packets_for(std::size_t reply, std::size_t w_length) {
  const std::size_t n = std::min(reply, w_length);
  std::vector<std::size_t> p(n / 64, 64);
  if (n % 64 != 0) p.push_back(n % 64);
  if (n < w_length && n > 0 && n % 64 == 0) p.push_back(0);
  return p;
}

std::uint16_t le16(std::span<const std::uint8_t> s, std::size_t at) {
  return static_cast<std::uint16_t>(s[at] | s[at + 1] << 8);
}

constexpr std::uint8_t kDevice = 0x01, kConfiguration = 0x02, kString = 0x03, kBos = 0x0F;

template <class Bus>
class UsbDeviceEnumeration : public ::testing::Test {};
TYPED_TEST_SUITE(UsbDeviceEnumeration, Buses, BusName);
template <class Bus>
class UsbDeviceControl : public ::testing::Test {};
TYPED_TEST_SUITE(UsbDeviceControl, Buses, BusName);
template <class Bus>
class UsbDeviceRequests : public ::testing::Test {};
TYPED_TEST_SUITE(UsbDeviceRequests, Buses, BusName);

TYPED_TEST(UsbDeviceEnumeration, WindowsSequenceGetsEveryDescriptorsExactBytesAndConfigures) {
  Rig<TypeParam> rig;
  auto& host = rig.host;
  ASSERT_TRUE(rig.bus.connected());

  // 1. GET_DESCRIPTOR(DEVICE, 64) at address 0, one packet read, then a second bus reset
  const auto device = find_descriptor(kDevice, 0, 0);
  ASSERT_EQ(device.size(), 18u);
  ControlResult r = host.control_in(get_descriptor(kDevice, 0, 64), 1);
  ASSERT_EQ(r.outcome, Outcome::ok);
  EXPECT_EQ(r.data, bytes_of(device));
  EXPECT_EQ(r.packets, std::vector<std::size_t>{18});
  host.reset();

  // 2. SET_ADDRESS, then everything at the new address
  ASSERT_EQ(host.control_out(set_address(7)).outcome, Outcome::ok);
  host.address = 7;
  EXPECT_EQ(rig.bus.address(), 7);
  EXPECT_EQ(rig.device.state(), DeviceState::address);

  r = host.control_in(get_descriptor(kDevice, 0, 18));
  ASSERT_EQ(r.outcome, Outcome::ok);
  EXPECT_EQ(r.data, bytes_of(device));

  // 3. the configuration: its 9-byte header, then all of it by wTotalLength and by 255
  const auto config = find_descriptor(kConfiguration, 0, 0);
  r = host.control_in(get_descriptor(kConfiguration, 0, 9));
  ASSERT_EQ(r.outcome, Outcome::ok);
  EXPECT_EQ(r.data, first(config, 9));
  const std::uint16_t total = le16(r.data, 2);
  ASSERT_EQ(total, config.size());
  for (std::uint16_t w_length : {total, std::uint16_t{255}}) {
    r = host.control_in(get_descriptor(kConfiguration, 0, w_length));
    ASSERT_EQ(r.outcome, Outcome::ok) << "wLength " << w_length;
    EXPECT_EQ(r.data, bytes_of(config));
    EXPECT_EQ(r.packets, packets_for(config.size(), w_length)) << "wLength " << w_length;
    EXPECT_FALSE(rig.bus.in_pending(0)) << "a packet left over after the status stage";
  }

  // 4. BOS: 5 bytes, then wTotalLength; then the MS OS 2.0 set by the vendor request, wIndex 7
  const auto bos = find_descriptor(kBos, 0, 0);
  r = host.control_in(get_descriptor(kBos, 0, 5));
  ASSERT_EQ(r.outcome, Outcome::ok);
  EXPECT_EQ(r.data, first(bos, 5));
  r = host.control_in(get_descriptor(kBos, 0, le16(r.data, 2)));
  ASSERT_EQ(r.outcome, Outcome::ok);
  EXPECT_EQ(r.data, bytes_of(bos));
  const auto msos = ms_os_20_descriptor_set();
  r = host.control_in({0xC0, kMsOs20VendorCode, 0, 7, static_cast<std::uint16_t>(msos.size())});
  ASSERT_EQ(r.outcome, Outcome::ok);
  EXPECT_EQ(r.data, bytes_of(msos));
  EXPECT_EQ(r.packets, packets_for(msos.size(), msos.size()));

  // 5. strings: the LANGID list, then the product and serial in 0x0409
  for (auto [index, langid] : {std::pair{0, 0}, std::pair{2, 0x0409}, std::pair{3, 0x0409}}) {
    const auto s = find_descriptor(kString, static_cast<std::uint8_t>(index),
                                   static_cast<std::uint16_t>(langid));
    ASSERT_FALSE(s.empty());
    r = host.control_in(get_descriptor(kString, static_cast<std::uint8_t>(index), 255,
                                       static_cast<std::uint16_t>(langid)));
    ASSERT_EQ(r.outcome, Outcome::ok) << "string " << index;
    EXPECT_EQ(r.data, bytes_of(s)) << "string " << index;
    EXPECT_EQ(r.packets, packets_for(s.size(), 255)) << "string " << index;
  }

  // 6. SET_CONFIGURATION(1): the stream endpoints open, OUT armed
  ASSERT_EQ(host.control_out(set_configuration(1)).outcome, Outcome::ok);
  EXPECT_TRUE(rig.device.configured());
  EXPECT_TRUE(rig.bus.open(1) && rig.bus.open(2));
  EXPECT_EQ(rig.bus.type(1), EndpointType::bulk);
  EXPECT_EQ(rig.bus.type(2), EndpointType::interrupt);
  EXPECT_EQ(rig.bus.max_packet(1), 64);
  EXPECT_EQ(rig.bus.max_packet(2), 64);
  EXPECT_TRUE(rig.bus.out_armed(1) && rig.bus.out_armed(2));

  // 7. the HID driver: SET_IDLE(0), then the report descriptor from the HID interface
  EXPECT_EQ(host.control_out({0x21, 0x0A, 0, 1, 0}).outcome, Outcome::ok);
  const auto report = find_descriptor(0x22, 0, 1);
  ASSERT_FALSE(report.empty());
  r = host.control_in(get_descriptor(0x22, 0, 255, 1, 0x81));
  ASSERT_EQ(r.outcome, Outcome::ok);
  EXPECT_EQ(r.data, bytes_of(report));
  r = host.control_in(get_descriptor(0x21, 0, 9, 1, 0x81));
  ASSERT_EQ(r.outcome, Outcome::ok);
  EXPECT_EQ(r.data, bytes_of(find_descriptor(0x21, 0, 1)));

  EXPECT_EQ(rig.device.counters().control_stalls, 0u);
  EXPECT_EQ(rig.device.counters().bus_resets, 2u);
  EXPECT_TRUE(rig.bus.violations().empty()) << rig.bus.violations().front();
}

TYPED_TEST(UsbDeviceControl, ZeroLengthPacketExactlyWhenTheReplyIsShortAndWholePackets) {
  Rig<TypeParam> rig;
  rig.configure();
  // GET_REPORT(Input) answers one 64-byte report (palp/protocol/usb.hpp kHidReportSize)
  const auto get_report = [](std::uint16_t w_length) {
    return SetupPacket{0xA1, 0x01, 0x0100, 1, w_length};
  };
  struct Case {
    std::uint16_t w_length;
    std::vector<std::size_t> packets;
  };
  for (const Case& c : {Case{64, {64}}, Case{65, {64, 0}}, Case{255, {64, 0}}, Case{63, {63}},
                        Case{1, {1}}}) {
    const ControlResult r = rig.host.control_in(get_report(c.w_length));
    ASSERT_EQ(r.outcome, Outcome::ok) << "wLength " << c.w_length;
    EXPECT_EQ(r.packets, c.packets) << "wLength " << c.w_length;
    EXPECT_EQ(r.data, std::vector<std::uint8_t>(c.packets[0], 0)) << "a report of padding";
    EXPECT_FALSE(rig.bus.in_pending(0)) << "wLength " << c.w_length << ": a ZLP too many";
  }
  // the 64-byte configuration block with wLength 255 (facts §1.11's example)
  const auto config = find_descriptor(kConfiguration, 0, 0);
  const ControlResult r = rig.host.control_in(get_descriptor(kConfiguration, 0, 255));
  EXPECT_EQ(r.packets, packets_for(config.size(), 255));
  EXPECT_TRUE(rig.bus.violations().empty());
}

TYPED_TEST(UsbDeviceControl, UnknownRequestStallsAndTheNextSetupRecovers) {
  Rig<TypeParam> rig;
  const std::vector<SetupPacket> refused = {
      {0x80, 0x33, 0, 0, 8},                           // unknown standard request
      {0xC0, kMsOs20VendorCode, 0, 8, 16},             // MS OS 2.0 wIndex 8 (alt. enumeration)
      {0xC1, kMsOs20VendorCode, 0, 7, 255},            // the set asked of an interface
      {0xC0, static_cast<std::uint8_t>(kMsOs20VendorCode + 1), 0, 7, 255},  // other code
      get_descriptor(0x06, 0, 10),                     // device qualifier: full speed only
      get_descriptor(kString, 200, 255, 0x0409),       // no such string
  };
  for (std::size_t k = 0; k < refused.size(); ++k) {
    const ControlResult r = rig.host.control_in(refused[k]);
    EXPECT_EQ(r.outcome, Outcome::stall) << "request " << k;
    EXPECT_TRUE(rig.bus.stalled(0)) << "request " << k;
    const ControlResult ok = rig.host.control_in(get_descriptor(kDevice, 0, 18));
    ASSERT_EQ(ok.outcome, Outcome::ok) << "after request " << k;
    EXPECT_EQ(ok.data, bytes_of(find_descriptor(kDevice, 0, 0)));
  }
  // requests not allowed in the Default state (no address yet)
  EXPECT_EQ(rig.host.control_out(set_configuration(1)).outcome, Outcome::stall);
  EXPECT_EQ(rig.host.control_in({0x80, 0x00, 0, 0, 2}).outcome, Outcome::stall);
  // and in the Address state: no such configuration, interfaces before configuration
  ASSERT_EQ(rig.host.control_out(set_address(3)).outcome, Outcome::ok);
  rig.host.address = 3;
  EXPECT_EQ(rig.host.control_out(set_configuration(2)).outcome, Outcome::stall);
  EXPECT_EQ(rig.host.control_in({0x81, 0x0A, 0, 0, 1}).outcome, Outcome::stall);
  EXPECT_EQ(rig.host.control_out({0x21, 0x0A, 0, 1, 0}).outcome, Outcome::stall);  // SET_IDLE
  ASSERT_EQ(rig.host.control_out(set_configuration(1)).outcome, Outcome::ok);
  // configured: no alternate setting 1, no interface 2, no endpoint 3, no boot protocol
  EXPECT_EQ(rig.host.control_out({0x01, 0x0B, 1, 0, 0}).outcome, Outcome::stall);
  EXPECT_EQ(rig.host.control_in({0x81, 0x0A, 0, 2, 1}).outcome, Outcome::stall);
  EXPECT_EQ(rig.host.control_in({0x82, 0x00, 0, 0x83, 2}).outcome, Outcome::stall);
  EXPECT_EQ(rig.host.control_out({0x21, 0x0B, 1, 1, 0}).outcome, Outcome::stall);
  EXPECT_EQ(rig.host.control_in(get_descriptor(0x22, 0, 255, 0, 0x81)).outcome, Outcome::stall);
  EXPECT_EQ(rig.device.counters().control_stalls, refused.size() + 2 + 3 + 5);
  EXPECT_EQ(rig.host.control_in(get_descriptor(kDevice, 0, 18)).outcome, Outcome::ok);
  EXPECT_TRUE(rig.bus.violations().empty());
}

TYPED_TEST(UsbDeviceControl, SetAddressTakesEffectOnlyAfterItsStatusStage) {
  Rig<TypeParam> rig;
  ASSERT_EQ(rig.bus.setup(0, set_address(42)), Handshake::ack);
  rig.device.service();
  EXPECT_EQ(rig.bus.address(), 0) << "applied before the status stage";
  EXPECT_TRUE(rig.bus.address_log().empty());
  // the status stage (the device's zero-length IN) still goes to address 0
  const InAnswer status = rig.bus.in(0, 0);
  ASSERT_EQ(status.handshake, Handshake::ack);
  EXPECT_TRUE(status.data.empty());
  rig.device.service();
  EXPECT_EQ(rig.bus.address(), 42);
  EXPECT_EQ(rig.bus.address_log(), std::vector<std::uint8_t>{42});
  // the old address is deaf now, the new one answers
  EXPECT_EQ(rig.bus.setup(0, get_descriptor(kDevice, 0, 18)), Handshake::no_answer);
  rig.host.address = 42;
  EXPECT_EQ(rig.host.control_in(get_descriptor(kDevice, 0, 18)).outcome, Outcome::ok);
}

TYPED_TEST(UsbDeviceControl, HostEndingTheDataStageEarlyCompletesTheTransfer) {
  Rig<TypeParam> rig;
  // a 64-byte configuration block asked with wLength 255: status after the first packet,
  // before the device's ZLP is taken
  const ControlResult r = rig.host.control_in(get_descriptor(kConfiguration, 0, 255), 1);
  ASSERT_EQ(r.outcome, Outcome::ok);
  EXPECT_EQ(r.packets.size(), 1u);
  const ControlResult next = rig.host.control_in(get_descriptor(kDevice, 0, 18));
  ASSERT_EQ(next.outcome, Outcome::ok);
  EXPECT_EQ(next.data, bytes_of(find_descriptor(kDevice, 0, 0)));
  EXPECT_TRUE(rig.bus.violations().empty());
}

TYPED_TEST(UsbDeviceControl, BusResetMidTransferStartsOverAtAddressZero) {
  Rig<TypeParam> rig;
  rig.configure();
  ASSERT_EQ(rig.bus.setup(5, get_descriptor(kConfiguration, 0, 255)), Handshake::ack);
  rig.device.service();
  rig.host.reset();
  EXPECT_EQ(rig.device.state(), DeviceState::default_state);
  EXPECT_FALSE(rig.device.configured());
  EXPECT_EQ(rig.bus.address(), 0);
  const ControlResult r = rig.host.control_in(get_descriptor(kDevice, 0, 64));
  ASSERT_EQ(r.outcome, Outcome::ok);
  EXPECT_EQ(r.data, bytes_of(find_descriptor(kDevice, 0, 0)));
  EXPECT_TRUE(rig.bus.violations().empty());
}

TYPED_TEST(UsbDeviceRequests, GetStatusAndConfigurationAndInterfaceAnswerTheState) {
  Rig<TypeParam> rig;
  ASSERT_EQ(rig.host.control_out(set_address(5)).outcome, Outcome::ok);
  rig.host.address = 5;
  EXPECT_EQ(rig.host.control_in({0x80, 0x08, 0, 0, 1}).data, std::vector<std::uint8_t>{0});
  const auto config = find_descriptor(kConfiguration, 0, 0);
  const std::uint8_t self_powered = (config[7] & 0x40) ? 1 : 0;  // bmAttributes bit 6
  EXPECT_EQ(rig.host.control_in({0x80, 0x00, 0, 0, 2}).data,
            (std::vector<std::uint8_t>{self_powered, 0}));
  ASSERT_EQ(rig.host.control_out(set_configuration(1)).outcome, Outcome::ok);
  EXPECT_EQ(rig.host.control_in({0x80, 0x08, 0, 0, 1}).data, std::vector<std::uint8_t>{1});
  EXPECT_EQ(rig.host.control_in({0x81, 0x00, 0, 1, 2}).data, (std::vector<std::uint8_t>{0, 0}));
  EXPECT_EQ(rig.host.control_in({0x81, 0x0A, 0, 0, 1}).data, std::vector<std::uint8_t>{0});
  EXPECT_EQ(rig.host.control_in({0x81, 0x0A, 0, 1, 1}).data, std::vector<std::uint8_t>{0});
  EXPECT_EQ(rig.host.control_out({0x01, 0x0B, 0, 1, 0}).outcome, Outcome::ok);
  // SET_CONFIGURATION(0): back to Address, the stream endpoints no longer answer with data
  ASSERT_EQ(rig.host.control_out(set_configuration(0)).outcome, Outcome::ok);
  EXPECT_EQ(rig.device.state(), DeviceState::address);
  EXPECT_EQ(rig.host.control_in({0x80, 0x08, 0, 0, 1}).data, std::vector<std::uint8_t>{0});
  const std::uint8_t byte = 0x55;
  EXPECT_EQ(rig.bus.out(5, 1, &byte, 1), Handshake::stall);
  EXPECT_EQ(rig.device.rx_waiting(), 0u);
}

TYPED_TEST(UsbDeviceRequests, EndpointHaltStallsAndClearingItResetsTheDataToggle) {
  Rig<TypeParam> rig;
  rig.configure();
  const std::uint8_t data[5] = {1, 2, 3, 4, 0};
  ASSERT_EQ(rig.bus.out(5, 1, data, sizeof data), Handshake::ack);
  rig.device.service();
  EXPECT_EQ(rig.bus.toggle_out(1), 1);  // DATA1 next
  const int opens = rig.bus.opens(1);

  ASSERT_EQ(rig.host.control_out({0x02, 0x03, 0, 0x81, 0}).outcome, Outcome::ok);  // SET_FEATURE
  EXPECT_EQ(rig.host.control_in({0x82, 0x00, 0, 0x81, 2}).data, (std::vector<std::uint8_t>{1, 0}));
  EXPECT_EQ(rig.host.control_in({0x82, 0x00, 0, 0x01, 2}).data, (std::vector<std::uint8_t>{0, 0}));
  EXPECT_TRUE(rig.bus.stalled(1));
  EXPECT_EQ(rig.bus.in(5, 1).handshake, Handshake::stall);

  ASSERT_EQ(rig.host.control_out({0x02, 0x01, 0, 0x81, 0}).outcome, Outcome::ok);  // CLEAR
  EXPECT_EQ(rig.host.control_in({0x82, 0x00, 0, 0x81, 2}).data, (std::vector<std::uint8_t>{0, 0}));
  EXPECT_FALSE(rig.bus.stalled(1));
  EXPECT_EQ(rig.bus.opens(1), opens + 1);
  EXPECT_EQ(rig.bus.toggle_out(1), 0);  // DATA0 again
  EXPECT_EQ(rig.bus.toggle_in(1), 0);
  EXPECT_TRUE(rig.bus.out_armed(1));
  // ep0 cannot be halted; clearing its halt is fine
  EXPECT_EQ(rig.host.control_out({0x02, 0x03, 0, 0x80, 0}).outcome, Outcome::stall);
  EXPECT_EQ(rig.host.control_out({0x02, 0x01, 0, 0x00, 0}).outcome, Outcome::ok);
  EXPECT_TRUE(rig.bus.violations().empty());
}

TYPED_TEST(UsbDeviceRequests, HidIdleAndSetReportFeedTheStream) {
  Rig<TypeParam> rig;
  rig.configure();
  EXPECT_EQ(rig.host.control_out({0x21, 0x0A, 0x7D00, 1, 0}).outcome, Outcome::ok);  // 500 ms
  EXPECT_EQ(rig.host.control_in({0xA1, 0x02, 0, 1, 1}).data, std::vector<std::uint8_t>{0x7D});
  std::vector<std::uint8_t> report(64, 0);
  for (std::size_t k = 0; k < 10; ++k) report[k] = static_cast<std::uint8_t>(k + 1);
  EXPECT_EQ(rig.host.control_out({0x21, 0x09, 0x0200, 1, 64}, report).outcome, Outcome::ok);
  EXPECT_EQ(rig.drain(), report);
  EXPECT_EQ(rig.device.sending_pipe(), StreamPipe::hid);
}

TYPED_TEST(UsbDeviceRequests, SetReportWaitsForRingRoomAndABusResetDropsIt) {
  Rig<TypeParam, 128, 2048> rig;  // a receive ring of two packets
  rig.configure();
  const std::vector<std::uint8_t> packet(64, 0x33);
  ASSERT_EQ(rig.bus.out(5, 1, packet.data(), 64), Handshake::ack);
  rig.device.service();
  // 64 bytes waiting, 64 promised to an armed endpoint: no room for a report
  const std::vector<std::uint8_t> report(64, 0x44);
  ASSERT_EQ(rig.bus.setup(5, {0x21, 0x09, 0x0200, 1, 64}), Handshake::ack);
  rig.device.service();
  ASSERT_EQ(rig.bus.out(5, 0, report.data(), 64), Handshake::ack);
  rig.device.service();
  EXPECT_EQ(rig.bus.in(5, 0).handshake, Handshake::nak) << "status stage before the ring had room";
  EXPECT_EQ(rig.drain(), packet);
  const InAnswer status = rig.bus.in(5, 0);
  EXPECT_EQ(status.handshake, Handshake::ack);
  EXPECT_TRUE(status.data.empty());
  rig.device.service();
  EXPECT_EQ(rig.drain(), report);

  // held again, then a bus reset: the transfer is gone, nothing is answered for it
  ASSERT_EQ(rig.bus.out(5, 1, packet.data(), 64), Handshake::ack);
  rig.device.service();
  ASSERT_EQ(rig.bus.setup(5, {0x21, 0x09, 0x0200, 1, 64}), Handshake::ack);
  rig.device.service();
  ASSERT_EQ(rig.bus.out(5, 0, report.data(), 64), Handshake::ack);
  rig.device.service();
  rig.host.reset();
  EXPECT_EQ(rig.drain(), packet);
  EXPECT_FALSE(rig.bus.in_pending(0));
  EXPECT_TRUE(rig.bus.violations().empty());
}

TYPED_TEST(UsbDeviceRequests, SuspendAndResumeAreTrackedAndEnumerationGoesOn) {
  Rig<TypeParam> rig;
  rig.configure();
  rig.bus.suspend();
  rig.device.service();
  EXPECT_TRUE(rig.device.suspended());
  rig.bus.resume();
  rig.device.service();
  EXPECT_FALSE(rig.device.suspended());
  EXPECT_EQ(rig.device.counters().suspends, 1u);
  EXPECT_TRUE(rig.device.configured());
  EXPECT_EQ(rig.host.control_in({0x80, 0x08, 0, 0, 1}).data, std::vector<std::uint8_t>{1});
}

}  // namespace
}  // namespace palp::usb::test
