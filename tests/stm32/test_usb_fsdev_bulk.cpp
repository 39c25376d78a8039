// SPDX-License-Identifier: Apache-2.0
// Bulk transfers of every size 0..4096 bytes through the FSDEV driver and the peripheral model,
// OUT, IN and both at once on endpoint 1, split into 64-byte packets: every byte arrives, in
// order, and the DATA0/DATA1 toggles alternate across all packets (the model's host counts every
// packet whose toggle disagrees; the fixture's TearDown checks none did).
//
// The transfer framing here is the test's own (full packets, then one short packet, a
// zero-length one when the size is a multiple of 64): the byte-stream and ZLP policy is the
// device core's (firmware/usb), not the driver's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "test_usb_fsdev_fixture.hpp"

namespace palp::stm32::test {
namespace {

constexpr std::size_t kMaxTransfer = 4096;
constexpr std::size_t kPacket = 64;

/// The packet sizes of one transfer of `size` bytes.
std::vector<std::size_t> packets_of(std::size_t size) {
  std::vector<std::size_t> sizes(size / kPacket, kPacket);
  sizes.push_back(size % kPacket);
  return sizes;
}

class UsbFsdevBulkTest : public UsbFsdevTest {
 protected:
  void SetUp() override {
    UsbFsdevTest::SetUp();
    model.set_logging(false);
    driver.open_endpoint(1, EndpointType::bulk, kPacket);
    driver.arm_out(1);
  }

  /// The device side: every pending event handled; OUT packets appended to `received` and the
  /// endpoint re-armed; the next IN packet of `to_send` written when the previous was taken.
  void service() {
    for (Event e = driver.poll(); e.kind != EventKind::none; e = driver.poll()) {
      ASSERT_EQ(e.endpoint, 1);
      if (e.kind == EventKind::out) {
        std::uint8_t bytes[kPacket];
        const std::size_t n = driver.read_out(1, bytes, sizeof bytes);
        received.insert(received.end(), bytes, bytes + n);
        driver.arm_out(1);
      } else {
        ASSERT_EQ(e.kind, EventKind::in_complete);
        in_busy = false;
      }
    }
    if (!in_busy && next_in < in_packets.size()) {
      const std::size_t size = in_packets[next_in++];
      driver.write_in(1, to_send.data() + in_offset, size);
      in_offset += size;
      in_busy = true;
    }
  }

  void queue_in(const std::vector<std::uint8_t>& bytes) {
    to_send = bytes;
    in_packets = packets_of(bytes.size());
    next_in = 0;
    in_offset = 0;
  }

  /// One host IN token (retried while NAKed); the packet's bytes appended to `taken`.
  void take_in() {
    const InPacket packet = model.in_retrying(1, [this] { service(); });
    ASSERT_EQ(packet.handshake, Handshake::ack);
    EXPECT_EQ(packet.pid_data, in_pid) << "IN packet " << in_count;
    in_pid ^= 1;
    ++in_count;
    taken.insert(taken.end(), packet.bytes.begin(), packet.bytes.end());
  }

  void send_out(std::span<const std::uint8_t> bytes) {
    ASSERT_EQ(model.out_retrying(1, bytes, [this] { service(); }), Handshake::ack);
  }

  std::vector<std::uint8_t> received, taken, to_send;
  std::vector<std::size_t> in_packets;
  std::size_t next_in = 0, in_offset = 0, in_count = 0;
  std::uint8_t in_pid = 0;
  bool in_busy = false;
};

TEST_F(UsbFsdevBulkTest, OutTransfersOfEverySizeUpTo4096ArriveWhole) {
  for (std::size_t size = 0; size <= kMaxTransfer; ++size) {
    const std::vector<std::uint8_t> sent = pattern(size, static_cast<unsigned>(size));
    received.clear();
    std::size_t offset = 0;
    for (std::size_t packet : packets_of(size)) {
      send_out(std::span(sent).subspan(offset, packet));
      offset += packet;
    }
    service();
    ASSERT_EQ(received, sent) << size;
  }
}

TEST_F(UsbFsdevBulkTest, InTransfersOfEverySizeUpTo4096AreTakenWholeWithAlternatingToggles) {
  for (std::size_t size = 0; size <= kMaxTransfer; ++size) {
    queue_in(pattern(size, static_cast<unsigned>(size + 11)));
    taken.clear();
    for (std::size_t i = 0; i < in_packets.size(); ++i) {
      take_in();
    }
    service();  // the last in_complete
    ASSERT_EQ(taken, to_send) << size;
    ASSERT_FALSE(in_busy) << size;
  }
}

TEST_F(UsbFsdevBulkTest, BothDirectionsAtOnceOfEverySizeUpTo4096) {
  for (std::size_t size = 0; size <= kMaxTransfer; ++size) {
    const std::vector<std::uint8_t> sent = pattern(size, static_cast<unsigned>(size + 3));
    queue_in(pattern(kMaxTransfer - size, static_cast<unsigned>(size + 5)));
    received.clear();
    taken.clear();
    const std::vector<std::size_t> out_packets = packets_of(size);
    std::size_t offset = 0;
    for (std::size_t i = 0; i < std::max(out_packets.size(), in_packets.size()); ++i) {
      if (i < out_packets.size()) {
        send_out(std::span(sent).subspan(offset, out_packets[i]));
        offset += out_packets[i];
      }
      if (i < in_packets.size()) {
        take_in();
      }
    }
    service();
    ASSERT_EQ(received, sent) << size;
    ASSERT_EQ(taken, to_send) << size;
  }
}

}  // namespace
}  // namespace palp::stm32::test
