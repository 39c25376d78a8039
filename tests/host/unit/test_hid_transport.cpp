// SPDX-License-Identifier: Apache-2.0
// hid://: the transport down to the hidapi calls, through a fake HidApi that records them: the
// exact 65 bytes of every report written (report ID 0x00, 64 stream bytes, zero padding only
// after a frame's delimiter), reads reassembling frames, timeouts, unplugging, choosing by serial
// number and the messages for each failure.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

#include "fake_usb_apis.hpp"
#include "palp/error.hpp"
#include "palp/protocol/frame.hpp"
#include "palp/protocol/usb.hpp"
#include "transport/hid_api.hpp"
#include "transport/usb_api.hpp"

namespace palp {
namespace {

using fakes::FakeHid;
using Bytes = std::vector<std::uint8_t>;
using namespace std::chrono_literals;

template <class M>
Bytes wire(const M& m, std::uint16_t seq) {
  Bytes out(proto::kMaxWireFrame);
  out.resize(proto::encode_message(m, seq, 0, out.data(), out.size()));
  return out;
}

/// The 65 bytes hidapi gets for one report carrying these stream bytes (zero-padded).
Bytes report(const Bytes& stream, std::size_t from, std::size_t to) {
  Bytes r(65, 0);
  std::copy(stream.begin() + static_cast<std::ptrdiff_t>(from),
            stream.begin() + static_cast<std::ptrdiff_t>(to), r.begin() + 1);
  return r;
}

std::shared_ptr<FakeHid> one_device(const std::string& serial = "PALP-0001") {
  auto f = std::make_shared<FakeHid>();
  f->devices.push_back(FakeHid::info(serial));
  return f;
}

std::unique_ptr<Transport> open(const std::shared_ptr<FakeHid>& f, const std::string& uri) {
  return detail::open_hid_transport(parse_uri(uri), 1000ms, f);
}

std::string open_error(const std::shared_ptr<FakeHid>& f, const std::string& uri) {
  try {
    open(f, uri);
  } catch (const ConnectionError& e) {
    return e.what();
  }
  return "no error";
}

TEST(HidTransport, PingFrameIsOneReportWithReportIdAndPadding) {
  auto f = one_device();
  auto t = open(f, "hid://PALP-0001");
  const Bytes frame = wire(proto::Ping{0x01020304u, 0x1122334455667788ull}, 7);
  ASSERT_LT(frame.size(), 64u);
  t->write(frame, 100ms);
  ASSERT_EQ(f->written.size(), 1u);
  Bytes expected{0x00};
  expected.insert(expected.end(), frame.begin(), frame.end());
  expected.resize(65, 0x00);
  EXPECT_EQ(f->written[0], expected);
  EXPECT_EQ(t->max_device_bytes_per_s(), proto::usb::kHidBytesPerS);
  EXPECT_EQ(t->uri(), "hid://PALP-0001");
  EXPECT_EQ(f->calls, (std::vector<std::string>{"enumerate 4617 1", "open PALP-0001"}));
}

TEST(HidTransport, ConsecutiveFramesFillReportsBackToBack) {
  auto f = one_device();
  auto t = open(f, "hid://");
  Bytes stream;
  for (std::uint32_t k = 0; stream.size() < 130; ++k) {
    const Bytes w = wire(proto::Ping{k, k}, static_cast<std::uint16_t>(k));
    stream.insert(stream.end(), w.begin(), w.end());
  }
  ASSERT_EQ(stream.back(), 0x00);
  t->write(stream, 100ms);
  const std::size_t reports = (stream.size() + 63) / 64;
  ASSERT_EQ(f->written.size(), reports);
  for (std::size_t r = 0; r < reports; ++r)
    EXPECT_EQ(f->written[r], report(stream, r * 64, std::min(stream.size(), r * 64 + 64)));
}

TEST(HidTransport, ExactlyOneHundredThirtyBytesEndingInADelimiter) {
  auto f = one_device();
  auto t = open(f, "hid://");
  Bytes stream(130);
  for (std::size_t k = 0; k < stream.size(); ++k) stream[k] = static_cast<std::uint8_t>(k + 1);
  stream.back() = 0x00;
  t->write(stream, 100ms);
  ASSERT_EQ(f->written.size(), 3u);
  EXPECT_EQ(f->written[0], report(stream, 0, 64));
  EXPECT_EQ(f->written[1], report(stream, 64, 128));
  EXPECT_EQ(f->written[2], report(stream, 128, 130));  // 0x82 0x00, then 62 bytes of padding
  EXPECT_EQ(f->written[2][1], 129);
  EXPECT_EQ(f->written[2][2], 0x00);
}

TEST(HidTransport, APartialFrameIsHeldNotPadded) {
  auto f = one_device();
  auto t = open(f, "hid://");
  const Bytes frame = wire(proto::Ping{5, 6}, 1);
  t->write(Bytes(frame.begin(), frame.begin() + 10), 100ms);
  EXPECT_TRUE(f->written.empty());  // no delimiter yet: nothing may be padded
  t->write(Bytes(frame.begin() + 10, frame.end()), 100ms);
  ASSERT_EQ(f->written.size(), 1u);
  EXPECT_EQ(f->written[0], report(frame, 0, frame.size()));
}

TEST(HidTransport, AFrameAndTheStartOfTheNextSendsThePaddedFrameAndHoldsTheRest) {
  auto f = one_device();
  auto t = open(f, "hid://");
  const Bytes a = wire(proto::Ping{1, 1}, 1), b = wire(proto::Ping{2, 2}, 2);
  Bytes first = a;
  first.insert(first.end(), b.begin(), b.begin() + 5);
  t->write(first, 100ms);
  ASSERT_EQ(f->written.size(), 1u);
  EXPECT_EQ(f->written[0], report(a, 0, a.size()));
  t->write(Bytes(b.begin() + 5, b.end()), 100ms);
  ASSERT_EQ(f->written.size(), 2u);
  EXPECT_EQ(f->written[1], report(b, 0, b.size()));
}

TEST(HidTransport, ReadsSplitAcrossReportsReassembleIntoTheFrame) {
  auto f = one_device();
  auto t = open(f, "hid://");
  Bytes stream = wire(proto::Pong{9, 10, 11}, 3);
  const Bytes second = wire(proto::Pong{12, 13, 14}, 4);
  stream.insert(stream.end(), second.begin(), second.end());
  stream.resize((stream.size() + 63) / 64 * 64, 0x00);  // the device pads the last report
  ASSERT_GE(stream.size(), 128u);
  for (std::size_t off = 0; off < stream.size(); off += 64)
    f->reports.emplace_back(64, Bytes(stream.begin() + static_cast<std::ptrdiff_t>(off),
                                      stream.begin() + static_cast<std::ptrdiff_t>(off + 64)));
  proto::FrameReader reader;
  std::vector<std::uint64_t> device_times;
  Bytes buf(256);
  for (std::size_t k = 0; k < stream.size() / 64 + 1; ++k) {
    const std::size_t n = t->read(buf, 100ms);
    reader.feed_messages(
        buf.data(), n,
        [&](const proto::FrameHeader&, const auto& m) {
          if constexpr (std::is_same_v<std::decay_t<decltype(m)>, proto::Pong>)
            device_times.push_back(m.device_time_us);
        },
        [](proto::Reject) { ADD_FAILURE() << "rejected"; });
  }
  EXPECT_EQ(device_times, (std::vector<std::uint64_t>{11, 14}));
  EXPECT_EQ(reader.pending(), 0u);
  for (const auto& [length, timeout] : f->reads) {
    EXPECT_EQ(length, 64u);
    EXPECT_EQ(timeout, 100);
  }
}

TEST(HidTransport, ASmallBufferIsServedFromOneReport) {
  auto f = one_device();
  auto t = open(f, "hid://");
  Bytes r(64);
  for (std::size_t k = 0; k < r.size(); ++k) r[k] = static_cast<std::uint8_t>(k);
  f->reports.emplace_back(64, r);
  Bytes got, buf(24);
  for (int k = 0; k < 3; ++k) {
    const std::size_t n = t->read(buf, 10ms);
    got.insert(got.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
  }
  EXPECT_EQ(got, r);
  EXPECT_EQ(f->reads.size(), 1u);
}

TEST(HidTransport, ATimeoutIsZeroBytes) {
  auto f = one_device();
  auto t = open(f, "hid://");
  Bytes buf(64);
  EXPECT_EQ(t->read(buf, 30ms), 0u);
  ASSERT_EQ(f->reads.size(), 1u);
  EXPECT_EQ(f->reads[0].second, 30);
}

TEST(HidTransport, UnpluggingIsAConnectionError) {
  auto f = one_device();
  auto t = open(f, "hid://");
  f->reports.emplace_back(-1, Bytes{});
  Bytes buf(64);
  try {
    t->read(buf, 10ms);
    FAIL() << "no error";
  } catch (const ConnectionError& e) {
    EXPECT_STREQ(e.what(),
                 "hid://PALP-0001: the controller was unplugged or stopped answering "
                 "(hid_read_timeout: unexpected poll error (device disconnected))");
  }
  f->write_result = -1;
  f->device_error = "hid_write: No such device";
  try {
    t->write(Bytes{1, 0}, 10ms);
    FAIL() << "no error";
  } catch (const ConnectionError& e) {
    EXPECT_STREQ(e.what(),
                 "hid://PALP-0001: writing a report failed (unplugged?): hid_write: No such "
                 "device");
  }
}

TEST(HidTransport, SerialSelection) {
  auto f = one_device("PALP-0001");
  f->devices.push_back(FakeHid::info("PALP-0002"));
  EXPECT_EQ(open_error(f, "hid://"),
            "hid://: 2 palp controllers are connected (serials: PALP-0001, PALP-0002); name one, "
            "e.g. hid://PALP-0001");
  EXPECT_EQ(open_error(f, "hid://NOPE"),
            "hid://NOPE: no palp controller with serial 'NOPE' (found: PALP-0001, PALP-0002)");
  f->calls.clear();
  auto t = open(f, "hid://PALP-0002");
  EXPECT_EQ(f->calls.back(), "open PALP-0002");
  EXPECT_EQ(open_error(std::make_shared<FakeHid>(), "hid://"),
            "hid://: no palp controller found (vid 0x1209 pid 0x0001); check that it is plugged "
            "in and powered");
}

TEST(HidTransport, PermissionDeniedSaysToInstallTheUdevRules) {
  auto f = one_device();
  f->open_error = "Failed to open a device with path '/dev/hidraw3': Permission denied";
  EXPECT_EQ(open_error(f, "hid://"),
            std::string("hid://PALP-0001: cannot open the controller: Failed to open a device "
                        "with path '/dev/hidraw3': Permission denied (") +
                detail::kPermissionHint + ")");
}

TEST(HidTransport, ClosesOnDestruction) {
  auto f = one_device();
  { auto t = open(f, "hid://"); }
  EXPECT_EQ(f->calls.back(), "close");
}

}  // namespace
}  // namespace palp
