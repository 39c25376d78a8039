// SPDX-License-Identifier: Apache-2.0
// The device core's stream pipes (firmware/usb/device.hpp "The stream"): bulk transfers of
// every size 0..4096 both ways with the ZLP rule of palp/protocol/usb.hpp, real frames encoded
// by the protocol library and read back by its frame reader (the SDK's) on the other end, over
// bulk and over HID reports, flow control with a slow app, and the choice of sending interface.
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <vector>

#include "device_rig.hpp"
#include "palp/protocol/frame.hpp"

namespace palp::usb::test {
namespace {

namespace pp = palp::proto;
constexpr std::uint8_t kAddress = 5, kBulk = 1, kHid = 2;
constexpr int kNakLimit = 100000;  // NAKs in a row before a test gives up (no progress)

std::vector<std::uint8_t> pattern(std::size_t n, std::uint32_t seed) {
  std::vector<std::uint8_t> v(n);
  std::uint32_t x = seed * 2654435761u + 1u;
  for (auto& b : v) {
    x = x * 1664525u + 1013904223u;
    b = static_cast<std::uint8_t>(x >> 24);
  }
  return v;
}

// The host writes `bytes` as the SDK's usb:// does: 64-byte packets, then a zero-length packet
// when the write is a non-zero multiple of 64. On a NAK, `on_nak` runs (the app reads) and the
// packet is sent again. Returns the NAKs seen.
template <class R>
int host_bulk_write(R& rig, const std::vector<std::uint8_t>& bytes, const std::function<void()>& on_nak) {
  int naks = 0;
  const auto send = [&](const std::uint8_t* p, std::size_t n) {
    for (int tries = 0;; ++tries) {
      const Handshake h = rig.bus.out(kAddress, kBulk, p, n);
      rig.device.service();
      if (h == Handshake::ack) return;
      ASSERT_EQ(h, Handshake::nak);
      ASSERT_LT(tries, kNakLimit) << "the device never took the packet";
      ++naks;
      on_nak();
    }
  };
  for (std::size_t off = 0; off < bytes.size(); off += 64)
    send(bytes.data() + off, std::min<std::size_t>(64, bytes.size() - off));
  if (!bytes.empty() && bytes.size() % 64 == 0) send(nullptr, 0);
  return naks;
}

struct InTransfer {
  std::vector<std::uint8_t> data;
  std::vector<std::size_t> packets;
};

// One host IN transfer of up to `max` bytes on endpoint `number`, as libusb's: IN tokens until
// a short packet (a zero-length one included) or `max` bytes. `feed` runs before every token
// (the app writing). Gives up after `nak_limit` NAKs in a row.
template <class R>
InTransfer host_in_transfer(R& rig, std::uint8_t number, std::size_t max,
                            const std::function<void()>& feed, int nak_limit = kNakLimit) {
  InTransfer t;
  for (int naks = 0; naks <= nak_limit && t.data.size() < max;) {
    feed();
    rig.device.service();
    const InAnswer a = rig.bus.in(kAddress, number);
    rig.device.service();
    if (a.handshake == Handshake::nak) {
      ++naks;
      continue;
    }
    EXPECT_EQ(a.handshake, Handshake::ack);
    if (a.handshake != Handshake::ack) break;
    naks = 0;
    t.packets.push_back(a.data.size());
    t.data.insert(t.data.end(), a.data.begin(), a.data.end());
    if (a.data.size() < 64) break;
  }
  return t;
}

// The app's writer: what is left of `bytes` goes into the device as room allows.
struct AppWriter {
  const std::vector<std::uint8_t>* bytes;
  std::size_t written = 0;
  template <class D>
  void operator()(D& device) {
    written += device.write(bytes->data() + written, bytes->size() - written);
  }
};

// Frames of payload sizes 0..1024 encoded by the protocol library, and their wire bytes.
struct Frames {
  std::vector<std::vector<std::uint8_t>> payloads;
  std::vector<std::uint8_t> wire;
};
Frames make_frames() {
  Frames f;
  std::vector<std::uint8_t> out(pp::kMaxWireFrame);
  const std::size_t sizes[] = {0, 1, 2, 51, 52, 53, 63, 64, 65, 100, 127, 128, 200, 254, 255,
                               256, 300, 511, 512, 700, 1000, 1023, 1024, 3, 9};
  std::uint16_t seq = 0;
  for (std::size_t size : sizes) {
    const auto payload = pattern(size, seq + 7u);
    const pp::FrameHeader h{pp::kProtocolMajor, pp::kProtocolMinor, 0x42, 0, seq++, 0};
    const std::size_t n = pp::encode_frame(h, payload.data(), size, out.data(), out.size());
    EXPECT_GT(n, 0u);
    f.payloads.push_back(payload);
    f.wire.insert(f.wire.end(), out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n));
  }
  return f;
}

// Feeds bytes to the protocol's frame reader; collects each accepted frame's payload, in order.
struct FrameSink {
  pp::FrameReader reader;
  std::vector<std::vector<std::uint8_t>> payloads;
  std::vector<std::uint16_t> seqs;
  int rejects = 0;
  void feed(const std::vector<std::uint8_t>& bytes) {
    reader.feed(
        bytes.data(), bytes.size(),
        [&](const pp::Frame& f) {
          payloads.emplace_back(f.payload, f.payload + f.header.payload_len);
          seqs.push_back(f.header.seq);
        },
        [&](pp::Reject) { ++rejects; });
  }
};

// Selects the sending pipe as the SDK does by talking first: one idle-line byte on `number`.
template <class R>
void host_talks_on(R& rig, std::uint8_t number) {
  std::vector<std::uint8_t> idle(number == kHid ? 64 : 1, 0x00);
  ASSERT_EQ(rig.bus.out(kAddress, number, idle.data(), idle.size()), Handshake::ack);
  rig.device.service();
  rig.drain();
}

template <class Bus>
class UsbDeviceStream : public ::testing::Test {};
TYPED_TEST_SUITE(UsbDeviceStream, Buses, BusName);

TYPED_TEST(UsbDeviceStream, BulkOutOfEverySize0To4096ArrivesWhole) {
  Rig<TypeParam> rig;
  rig.configure();
  for (std::size_t n = 0; n <= 4096; ++n) {
    const auto bytes = pattern(n, static_cast<std::uint32_t>(n));
    std::vector<std::uint8_t> got;
    host_bulk_write(rig, bytes, [&] {
      const auto part = rig.drain();
      got.insert(got.end(), part.begin(), part.end());
    });
    const auto rest = rig.drain();
    got.insert(got.end(), rest.begin(), rest.end());
    ASSERT_EQ(got, bytes) << "write of " << n << " bytes";
  }
  EXPECT_GT(rig.device.counters().rx_pauses, 0u);  // the 1 KiB ring filled: flow control
  EXPECT_TRUE(rig.bus.violations().empty());
}

TYPED_TEST(UsbDeviceStream, BulkInOfEverySize0To4096EndsWithAShortOrZeroLengthPacket) {
  Rig<TypeParam> rig;
  rig.configure();
  host_talks_on(rig, kBulk);
  for (std::size_t n = 0; n <= 4096; ++n) {
    const auto bytes = pattern(n, static_cast<std::uint32_t>(n) + 99u);
    AppWriter app{&bytes};
    const InTransfer t = host_in_transfer(rig, kBulk, 8192, [&] { app(rig.device); }, 3);
    ASSERT_EQ(t.data, bytes) << "n " << n;
    std::vector<std::size_t> expected(n / 64, 64);  // usb.hpp: the run ends short, or with a ZLP
    if (n % 64 != 0) expected.push_back(n % 64);
    else if (n > 0) expected.push_back(0);
    ASSERT_EQ(t.packets, expected) << "n " << n;
    ASSERT_EQ(rig.bus.in(kAddress, kBulk).handshake, Handshake::nak) << "a packet too many, n " << n;
  }
  EXPECT_TRUE(rig.bus.violations().empty());
}

TYPED_TEST(UsbDeviceStream, FramesBothWaysOverBulkPassTheProtocolsFrameReader) {
  Rig<TypeParam> rig;
  rig.configure();
  const Frames frames = make_frames();
  // host -> device: one write per frame, as the SDK writes them
  FrameSink at_device;
  for (std::size_t k = 0, off = 0; k < frames.payloads.size(); ++k) {
    const std::size_t end = std::find(frames.wire.begin() + static_cast<std::ptrdiff_t>(off),
                                      frames.wire.end(), 0x00) - frames.wire.begin() + 1;
    std::vector<std::uint8_t> frame(frames.wire.begin() + static_cast<std::ptrdiff_t>(off),
                                    frames.wire.begin() + static_cast<std::ptrdiff_t>(end));
    host_bulk_write(rig, frame, [&] { at_device.feed(rig.drain()); });
    off = end;
  }
  at_device.feed(rig.drain());
  EXPECT_EQ(at_device.payloads, frames.payloads);
  EXPECT_EQ(at_device.rejects, 0);

  // device -> host: the app writes the frames as room allows; the host reads transfers of 4 KiB
  AppWriter app{&frames.wire};
  FrameSink at_host;
  std::size_t received = 0;
  for (int transfers = 0; received < frames.wire.size() && transfers < 1000; ++transfers) {
    const InTransfer t = host_in_transfer(rig, kBulk, 4096, [&] { app(rig.device); }, 3);
    received += t.data.size();
    at_host.feed(t.data);
  }
  EXPECT_EQ(received, frames.wire.size());
  EXPECT_EQ(at_host.payloads, frames.payloads);
  EXPECT_EQ(at_host.rejects, 0);
  EXPECT_EQ(rig.device.counters().tx_bytes, frames.wire.size());
  EXPECT_TRUE(rig.bus.violations().empty());
}

TYPED_TEST(UsbDeviceStream, FramesOverHidReportsArePaddedOnlyAfterADelimiter) {
  Rig<TypeParam> rig;
  rig.configure();
  host_talks_on(rig, kHid);
  const Frames frames = make_frames();
  AppWriter app{&frames.wire};
  FrameSink at_host;
  std::size_t reports = 0;
  for (int naks = 0; app.written < frames.wire.size() || rig.device.tx_waiting() > 0;) {
    app(rig.device);
    rig.device.service();
    const InAnswer a = rig.bus.in(kAddress, kHid);
    rig.device.service();
    if (a.handshake == Handshake::nak) {
      ASSERT_LT(++naks, 10) << "the device holds bytes it could send";
      continue;
    }
    ASSERT_EQ(a.handshake, Handshake::ack);
    ASSERT_EQ(a.data.size(), 64u) << "every report is 64 bytes";
    ++reports;
    at_host.feed(a.data);
  }
  EXPECT_EQ(at_host.payloads, frames.payloads);
  EXPECT_EQ(at_host.rejects, 0) << "padding inside a frame would have ended it early";
  EXPECT_GE(reports * 64, frames.wire.size());

  // and host -> device: 64-byte reports, each frame zero-padded after its delimiter
  FrameSink at_device;
  for (std::size_t off = 0; off < frames.wire.size(); off += 64) {
    std::vector<std::uint8_t> report(64, 0);
    std::copy_n(frames.wire.begin() + static_cast<std::ptrdiff_t>(off),
                std::min<std::size_t>(64, frames.wire.size() - off), report.begin());
    int tries = 0;
    while (rig.bus.out(kAddress, kHid, report.data(), 64) == Handshake::nak) {
      at_device.feed(rig.drain());
      ASSERT_LT(++tries, 10);
    }
    rig.device.service();
  }
  at_device.feed(rig.drain());
  EXPECT_EQ(at_device.payloads, frames.payloads);
  EXPECT_EQ(at_device.rejects, 0);
}

TYPED_TEST(UsbDeviceStream, HidReportWaitsForTheEndOfAFrame) {
  Rig<TypeParam> rig;
  rig.configure();
  host_talks_on(rig, kHid);
  const std::uint8_t start[] = {0x11, 0x22, 0x33};
  ASSERT_EQ(rig.device.write(start, sizeof start), sizeof start);
  rig.device.service();
  EXPECT_EQ(rig.bus.in(kAddress, kHid).handshake, Handshake::nak);
  const std::uint8_t end[] = {0x44, 0x00, 0x55};  // the frame's end, and the next one's start
  ASSERT_EQ(rig.device.write(end, sizeof end), sizeof end);
  rig.device.service();
  const InAnswer a = rig.bus.in(kAddress, kHid);
  ASSERT_EQ(a.handshake, Handshake::ack);
  std::vector<std::uint8_t> expected(64, 0);
  expected[0] = 0x11, expected[1] = 0x22, expected[2] = 0x33, expected[3] = 0x44;
  EXPECT_EQ(a.data, expected);
  rig.device.service();
  EXPECT_EQ(rig.device.tx_waiting(), 1u);  // 0x55 waits for its frame's end
}

TYPED_TEST(UsbDeviceStream, SlowAppLosesNothingTheHostIsHeldOffInstead) {
  Rig<TypeParam, 128, 2048> rig;  // a receive ring of two packets
  rig.configure();
  const auto bytes = pattern(4096, 4);
  std::vector<std::uint8_t> got;
  const int naks = host_bulk_write(rig, bytes, [&] {
    std::uint8_t some[7];  // the app reads 7 bytes at a time
    const std::size_t n = rig.device.read(some, sizeof some);
    got.insert(got.end(), some, some + n);
    rig.device.service();
  });
  const auto rest = rig.drain();
  got.insert(got.end(), rest.begin(), rest.end());
  EXPECT_EQ(got, bytes);
  EXPECT_GT(naks, 0);
  EXPECT_GT(rig.device.counters().rx_pauses, 0u);
  EXPECT_EQ(rig.device.counters().rx_bytes, bytes.size());

  // both OUT endpoints at once into the small ring: never more armed than there is room for
  std::vector<std::uint8_t> report(64, 0x01);
  EXPECT_EQ(rig.bus.out(kAddress, kBulk, report.data(), 64), Handshake::ack);
  EXPECT_EQ(rig.bus.out(kAddress, kHid, report.data(), 64), Handshake::ack);
  rig.device.service();
  EXPECT_EQ(rig.bus.out(kAddress, kBulk, report.data(), 64), Handshake::nak);
  EXPECT_EQ(rig.bus.out(kAddress, kHid, report.data(), 64), Handshake::nak);
  EXPECT_EQ(rig.drain().size(), 128u);
  EXPECT_TRUE(rig.bus.violations().empty());
}

TYPED_TEST(UsbDeviceStream, NothingIsSentBeforeTheHostTalksThenTheLastTalkedInterfaceSends) {
  Rig<TypeParam> rig;
  rig.configure();
  const Frames frames = make_frames();
  const std::vector<std::uint8_t> first(frames.wire.begin(),
                                        std::find(frames.wire.begin(), frames.wire.end(), 0x00) + 1);
  ASSERT_LE(first.size(), 64u);
  ASSERT_EQ(rig.device.write(first.data(), first.size()), first.size());
  rig.device.service();
  EXPECT_EQ(rig.bus.in(kAddress, kBulk).handshake, Handshake::nak);
  EXPECT_EQ(rig.bus.in(kAddress, kHid).handshake, Handshake::nak);
  EXPECT_EQ(rig.device.sending_pipe(), StreamPipe::none);

  // the host talks on HID: the frame goes into a report, which the host does not take...
  host_talks_on(rig, kHid);
  EXPECT_EQ(rig.device.sending_pipe(), StreamPipe::hid);
  EXPECT_TRUE(rig.bus.in_pending(kHid));
  // ...then talks on bulk: the frame is sent again there, whole
  host_talks_on(rig, kBulk);
  EXPECT_EQ(rig.device.sending_pipe(), StreamPipe::bulk);
  const InTransfer t = host_in_transfer(rig, kBulk, 4096, [] {}, 3);
  FrameSink at_host;
  at_host.feed(t.data);
  ASSERT_EQ(at_host.payloads.size(), 1u);
  EXPECT_EQ(at_host.payloads[0], frames.payloads[0]);
  EXPECT_EQ(rig.device.counters().pipe_switches, 1u);
  EXPECT_EQ(rig.device.counters().tx_resent_bytes, first.size());
  // the stale report, taken late, changes nothing
  EXPECT_EQ(rig.bus.in(kAddress, kHid).handshake, Handshake::ack);
  rig.device.service();
  EXPECT_EQ(rig.device.tx_waiting(), 0u);
  EXPECT_EQ(rig.device.counters().tx_bytes, first.size());
  EXPECT_TRUE(rig.bus.violations().empty());
}

}  // namespace
}  // namespace palp::usb::test
