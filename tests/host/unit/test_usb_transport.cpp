// SPDX-License-Identifier: Apache-2.0
// usb://: the transport down to the libusb calls, through a fake UsbApi that records them: the
// exact bytes, endpoints, lengths and timeouts of every bulk transfer, the zero-length packet
// rule, reads reassembling frames, timeouts, unplugging, choosing by serial number and the
// messages for each failure.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "fake_usb_apis.hpp"
#include "palp/error.hpp"
#include "palp/protocol/frame.hpp"
#include "palp/protocol/usb.hpp"
#include "transport/usb_api.hpp"

namespace palp {
namespace {

using fakes::FakeUsb;
using ::testing::ElementsAre;
using namespace std::chrono_literals;

template <class M>
std::vector<std::uint8_t> wire(const M& m, std::uint16_t seq) {
  std::vector<std::uint8_t> out(proto::kMaxWireFrame);
  out.resize(proto::encode_message(m, seq, 0, out.data(), out.size()));
  return out;
}

std::shared_ptr<FakeUsb> one_device(const std::string& serial = "PALP-0001") {
  auto f = std::make_shared<FakeUsb>();
  f->devices.push_back({FakeUsb::desc(), serial, "palp probe controller"});
  return f;
}

std::unique_ptr<Transport> open(const std::shared_ptr<FakeUsb>& f, const std::string& uri) {
  return detail::open_usb_transport(parse_uri(uri), 1000ms, f);
}

std::string open_error(const std::shared_ptr<FakeUsb>& f, const std::string& uri) {
  try {
    open(f, uri);
  } catch (const ConnectionError& e) {
    return e.what();
  }
  return "no error";
}

TEST(UsbTransport, OpensClaimsTheVendorInterfaceAndReleasesItOnClose) {
  auto f = one_device();
  f->devices[0].kernel_driver = true;
  { auto t = open(f, "usb://"); }
  EXPECT_THAT(f->calls, ElementsAre("init", "get_device_list", "open 0", "free_device_list",
                                    "kernel_driver_active 0 0", "detach_kernel_driver 0 0",
                                    "claim_interface 0 0", "release_interface 0 0", "close 0",
                                    "exit"));
}

TEST(UsbTransport, PingFrameIsOneBulkOutTransferOfItsWireBytes) {
  auto f = one_device();
  auto t = open(f, "usb://PALP-0001");
  const auto frame = wire(proto::Ping{0x01020304u, 0x1122334455667788ull}, 7);
  ASSERT_FALSE(frame.empty());
  ASSERT_NE(frame.size() % 64, 0u);
  t->write(frame, 250ms);
  ASSERT_EQ(f->transfers.size(), 1u);
  EXPECT_EQ(f->transfers[0].endpoint, 0x01);
  EXPECT_EQ(f->transfers[0].length, static_cast<int>(frame.size()));
  EXPECT_EQ(f->transfers[0].timeout_ms, 250u);
  EXPECT_EQ(f->transfers[0].bytes, frame);
  EXPECT_EQ(t->max_device_bytes_per_s(), proto::usb::kBulkBytesPerS);
  EXPECT_EQ(t->uri(), "usb://PALP-0001");
}

TEST(UsbTransport, A130ByteWriteIsOneTransferWithoutZeroLengthPacket) {
  auto f = one_device();
  auto t = open(f, "usb://");
  std::vector<std::uint8_t> bytes(130);
  for (std::size_t k = 0; k < bytes.size(); ++k) bytes[k] = static_cast<std::uint8_t>(k + 1);
  t->write(bytes, 100ms);
  ASSERT_EQ(f->transfers.size(), 1u);
  EXPECT_EQ(f->transfers[0].bytes, bytes);
}

TEST(UsbTransport, AWriteOfWholePacketsEndsWithAZeroLengthPacket) {
  auto f = one_device();
  auto t = open(f, "usb://");
  const std::vector<std::uint8_t> bytes(128, 0x5A);
  t->write(bytes, 100ms);
  ASSERT_EQ(f->transfers.size(), 2u);
  EXPECT_EQ(f->transfers[0].bytes, bytes);
  EXPECT_EQ(f->transfers[1].endpoint, 0x01);
  EXPECT_EQ(f->transfers[1].length, 0);
  EXPECT_GE(f->transfers[1].timeout_ms, 1u);
  EXPECT_LE(f->transfers[1].timeout_ms, 100u);
  f->transfers.clear();
  t->write({}, 100ms);  // nothing: no transfer, no ZLP
  EXPECT_TRUE(f->transfers.empty());
}

TEST(UsbTransport, ALongWriteIsCutInto16KiBTransfers) {
  auto f = one_device();
  auto t = open(f, "usb://");
  std::vector<std::uint8_t> bytes(20000);
  for (std::size_t k = 0; k < bytes.size(); ++k) bytes[k] = static_cast<std::uint8_t>(k * 7);
  t->write(bytes, 1000ms);
  ASSERT_EQ(f->transfers.size(), 2u);  // 20000 is not a multiple of 64: no ZLP
  EXPECT_EQ(f->transfers[0].length, 16384);
  EXPECT_EQ(f->transfers[1].length, 20000 - 16384);
  std::vector<std::uint8_t> joined = f->transfers[0].bytes;
  joined.insert(joined.end(), f->transfers[1].bytes.begin(), f->transfers[1].bytes.end());
  EXPECT_EQ(joined, bytes);
}

TEST(UsbTransport, APartialTransferIsContinuedWithTheRest) {
  auto f = one_device();
  auto t = open(f, "usb://");
  f->out.push_back({0, 64});
  std::vector<std::uint8_t> bytes(130, 1);
  t->write(bytes, 100ms);
  ASSERT_EQ(f->transfers.size(), 2u);
  EXPECT_EQ(f->transfers[1].length, 66);
}

TEST(UsbTransport, AWriteTheDeviceDoesNotTakeTimesOut) {
  auto f = one_device();
  auto t = open(f, "usb://");
  f->out.push_back({detail::kUsbErrorTimeout, 64});
  try {
    t->write(std::vector<std::uint8_t>(130, 1), 250ms);
    FAIL() << "no timeout";
  } catch (const TimeoutError& e) {
    EXPECT_EQ(e.waited_for(), "the controller at usb://PALP-0001 to take 130 bytes (64 taken)");
    EXPECT_DOUBLE_EQ(e.timeout_s(), 0.25);
  }
}

TEST(UsbTransport, ReadsSplitAcrossTransfersReassembleIntoTheFrame) {
  auto f = one_device();
  auto t = open(f, "usb://");
  const auto frame = wire(proto::Pong{9, 10, 11}, 3);
  const std::size_t half = frame.size() / 2;
  f->in.push_back({0, {frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(half)}});
  f->in.push_back({0, {frame.begin() + static_cast<std::ptrdiff_t>(half), frame.end()}});
  proto::FrameReader reader;
  int pongs = 0;
  std::vector<std::uint8_t> buf(4096);
  for (int k = 0; k < 3; ++k) {
    const std::size_t n = t->read(buf, 100ms);
    reader.feed_messages(
        buf.data(), n,
        [&](const proto::FrameHeader& h, const auto& m) {
          if constexpr (std::is_same_v<std::decay_t<decltype(m)>, proto::Pong>) {
            EXPECT_EQ(h.seq, 3);
            EXPECT_EQ(m.device_time_us, 11u);
            ++pongs;
          }
        },
        [](proto::Reject) { ADD_FAILURE() << "rejected"; });
  }
  EXPECT_EQ(pongs, 1);
  ASSERT_EQ(f->transfers.size(), 3u);
  for (const auto& x : f->transfers) {
    EXPECT_EQ(x.endpoint, 0x81);
    EXPECT_EQ(x.length, 4096);
    EXPECT_EQ(x.timeout_ms, 100u);
  }
}

TEST(UsbTransport, ReadLengthIsAWholeNumberOfPackets) {
  auto f = one_device();
  auto t = open(f, "usb://");
  std::vector<std::uint8_t> buf(100);
  t->read(buf, 5ms);
  std::vector<std::uint8_t> big(1 << 20);
  t->read(big, 5ms);
  ASSERT_EQ(f->transfers.size(), 2u);
  EXPECT_EQ(f->transfers[0].length, 64);
  EXPECT_EQ(f->transfers[1].length, 16384);
}

TEST(UsbTransport, ASmallBufferIsServedFromOnePacket) {
  auto f = one_device();
  auto t = open(f, "usb://");
  std::vector<std::uint8_t> packet(40);
  for (std::size_t k = 0; k < packet.size(); ++k) packet[k] = static_cast<std::uint8_t>(k);
  f->in.push_back({0, packet});
  std::vector<std::uint8_t> got, buf(16);
  for (int k = 0; k < 3; ++k) {
    const std::size_t n = t->read(buf, 10ms);
    got.insert(got.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
  }
  EXPECT_EQ(got, packet);
  ASSERT_EQ(f->transfers.size(), 1u);
  EXPECT_EQ(f->transfers[0].length, 64);
}

TEST(UsbTransport, ATimeoutReturnsWhatCameOrNothing) {
  auto f = one_device();
  auto t = open(f, "usb://");
  std::vector<std::uint8_t> buf(256);
  EXPECT_EQ(t->read(buf, 20ms), 0u);
  f->in.push_back({detail::kUsbErrorTimeout, {1, 2, 3}});
  EXPECT_EQ(t->read(buf, 20ms), 3u);
  EXPECT_EQ(t->read(buf, 0ms), 0u);
  EXPECT_EQ(f->transfers.back().timeout_ms, 1u);  // never 0: that is "no timeout" to libusb
}

TEST(UsbTransport, UnpluggingIsAConnectionError) {
  auto f = one_device();
  auto t = open(f, "usb://");
  f->in.push_back({detail::kUsbErrorNoDevice, {}});
  std::vector<std::uint8_t> buf(64);
  try {
    t->read(buf, 10ms);
    FAIL() << "no error";
  } catch (const ConnectionError& e) {
    EXPECT_STREQ(e.what(),
                 "usb://PALP-0001: the controller was unplugged (LIBUSB_ERROR_NO_DEVICE)");
  }
  f->out.push_back({detail::kUsbErrorNoDevice, 0});
  EXPECT_THROW(t->write(std::vector<std::uint8_t>{1, 0}, 10ms), ConnectionError);
}

std::shared_ptr<FakeUsb> two_devices() {
  auto f = one_device("PALP-0001");
  f->devices.push_back({FakeUsb::desc(), "PALP-0002", "palp probe controller"});
  f->devices.push_back({FakeUsb::desc(0x0102, 0x1209, 0x0002), "OTHER", "not palp"});
  return f;
}

TEST(UsbTransport, ASerialPicksItsControllerAndClosesTheOthers) {
  auto f = two_devices();
  auto t = open(f, "usb://PALP-0002");
  EXPECT_THAT(f->calls, ElementsAre("init", "get_device_list", "open 0", "open 1",
                                    "free_device_list", "close 0", "kernel_driver_active 1 0",
                                    "claim_interface 1 0"));
}

TEST(UsbTransport, NoSerialWithSeveralControllersListsThem) {
  auto f = two_devices();
  EXPECT_EQ(open_error(f, "usb://"),
            "usb://: 2 palp controllers are connected (serials: PALP-0001, PALP-0002); name one, "
            "e.g. usb://PALP-0001");
  EXPECT_THAT(f->calls, ElementsAre("init", "get_device_list", "open 0", "open 1",
                                    "free_device_list", "close 0", "close 1", "exit"));
}

TEST(UsbTransport, AnUnknownSerialIsNamed) {
  EXPECT_EQ(open_error(two_devices(), "usb://PALP-9"),
            "usb://PALP-9: no palp controller with serial 'PALP-9' (found: PALP-0001, "
            "PALP-0002)");
}

TEST(UsbTransport, NoControllerSaysWhatWasLookedFor) {
  auto f = std::make_shared<FakeUsb>();
  EXPECT_EQ(open_error(f, "usb://"),
            "usb://: no palp controller found (vid 0x1209 pid 0x0001); check that it is plugged "
            "in and powered");
}

TEST(UsbTransport, PermissionDeniedSaysToInstallTheUdevRules) {
  auto f = one_device();
  f->devices[0].open_error = detail::kUsbErrorAccess;
  EXPECT_EQ(open_error(f, "usb://"),
            std::string("usb://: cannot open the controller: LIBUSB_ERROR_ACCESS (permission "
                        "denied: ") + detail::kPermissionHint + ")");
  EXPECT_THAT(open_error(f, "usb://PALP-0001"),
              ::testing::HasSubstr("(found: none readable; 1 could not be opened: "
                                   "LIBUSB_ERROR_ACCESS (permission denied: install the udev "
                                   "rules (host/udev/70-palp.rules"));
}

TEST(UsbTransport, AClaimedInterfacePointsToHid) {
  auto f = one_device();
  f->claim_result = detail::kUsbErrorBusy;
  EXPECT_EQ(open_error(f, "usb://"),
            "usb://PALP-0001: cannot claim the vendor interface 0: LIBUSB_ERROR_BUSY (another "
            "program holds it, perhaps another palpctl or SDK session; close it, or reach the "
            "controller over hid://PALP-0001)");
  EXPECT_EQ(f->calls.back(), "exit");
}

TEST(UsbTransport, NoUsbOnThisMachine) {
  auto f = one_device();
  f->init_result = detail::kUsbErrorOther;
  EXPECT_EQ(open_error(f, "usb://"),
            "usb://: USB is not available on this machine (libusb_init: LIBUSB_ERROR_OTHER)");
}

TEST(UsbTransport, IdentityFromTheUriOrTheEnvironment) {
  auto f = std::make_shared<FakeUsb>();
  f->devices.push_back({FakeUsb::desc(0x0100, 0x1234, 0x5678), "X1", ""});
  EXPECT_NO_THROW(open(f, "usb://?vid=0x1234&pid=0x5678"));
  ::setenv("PALP_USB_VID", "1234", 1);
  ::setenv("PALP_USB_PID", "0x5678", 1);
  EXPECT_NO_THROW(open(f, "usb://X1"));
  ::unsetenv("PALP_USB_VID");
  ::unsetenv("PALP_USB_PID");
  EXPECT_THAT(open_error(f, "usb://X1"), ::testing::HasSubstr("no palp controller found"));
}

}  // namespace
}  // namespace palp
