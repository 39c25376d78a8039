// SPDX-License-Identifier: Apache-2.0
// The SDK's usb:// and hid:// transports and its discovery, unmodified, against the device stack
// and the firmware core on the rig's bus (board_rig.hpp, rig_apis.hpp): what the issue asks,
// "the SDK's transports talk to the board as they are". Each test builds its own board; the
// device thread runs the control tick in wall time, so a stream's sample count is its duration.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "palp/discovery.hpp"
#include "palp/error.hpp"
#include "palp/probe.hpp"
#include "palp/protocol/usb.hpp"
#include "palp/usb/descriptors.hpp"
#include "rig_apis.hpp"
#include "transport/hid_api.hpp"
#include "transport/usb_api.hpp"

namespace palp::usb_e2e {
namespace {

using namespace std::chrono_literals;
namespace pu = palp::proto::usb;

constexpr auto kOpenTimeout = 2000ms;

std::unique_ptr<Transport> open_usb(const std::shared_ptr<BoardRig>& rig, const std::string& uri) {
  return detail::open_usb_transport(parse_uri(uri), kOpenTimeout, std::make_shared<RigUsbApi>(rig));
}
std::unique_ptr<Transport> open_hid(const std::shared_ptr<BoardRig>& rig, const std::string& uri) {
  return detail::open_hid_transport(parse_uri(uri), kOpenTimeout, std::make_shared<RigHidApi>(rig));
}

/// What a stream delivered: samples in order and every gap record.
struct Streamed {
  std::vector<Sample> samples;
  std::vector<Gap> gaps;
};

/// Streams `settings` until `count` samples (or gaps covering them) came, then stops.
Streamed stream(Probe& probe, const StreamSettings& settings, std::size_t count) {
  Streamed s;
  probe.configure_stream(settings);
  probe.start_stream();
  const auto deadline = std::chrono::steady_clock::now() + 20s;  // far beyond the test's 0.5 s
  std::uint64_t covered = 0;
  while (covered < count && std::chrono::steady_clock::now() < deadline) {
    const auto item = probe.next(1s);
    if (!item) continue;
    if (const auto* sample = std::get_if<Sample>(&*item)) {
      s.samples.push_back(*sample);
      ++covered;
    } else {
      s.gaps.push_back(std::get<Gap>(*item));
      covered += std::get<Gap>(*item).count;
    }
  }
  probe.stop_stream();
  return s;
}

/// Indices 0, 1, 2, ... with device times one period apart: nothing lost, repeated or reordered.
void expect_continuous(const Streamed& s, std::size_t count, double period_s) {
  EXPECT_TRUE(s.gaps.empty()) << s.gaps.size() << " gaps, the first of "
                              << (s.gaps.empty() ? 0 : s.gaps.front().count) << " samples from "
                              << gap_source_name(s.gaps.empty() ? GapSource::transport
                                                                : s.gaps.front().source);
  ASSERT_GE(s.samples.size(), count);
  for (std::size_t k = 0; k < s.samples.size(); ++k) {
    ASSERT_EQ(s.samples[k].index, k) << "sample " << k;
    if (k > 0) {
      ASSERT_NEAR(s.samples[k].t_device_s - s.samples[k - 1].t_device_s, period_s, 1e-6) << k;
    }
  }
}

/// Printed, not judged: how the host kept up on this machine.
void print_rig(BoardRig& rig, const char* what) {
  const usb::DeviceCounters c = rig.device_counters();
  std::printf("[ usb_e2e  ] %s: %llu control ticks, %llu held for an undrained host; device "
              "tx %u bytes, rx %u bytes, OUT pauses %u\n",
              what, static_cast<unsigned long long>(rig.ticks()),
              static_cast<unsigned long long>(rig.ticks_held()), c.tx_bytes, c.rx_bytes,
              c.rx_pauses);
}

TEST(UsbE2eDiscovery, ListsTheBoardOnceWithTheSerialItsDescriptorsServeAndBothUris) {
  const RigOptions options;
  auto rig = std::make_shared<BoardRig>(options);
  RigUsbApi usb(rig);
  RigHidApi hid(rig);
  const auto listed = detail::list_devices_with(DiscoveryOptions{}, &usb, &hid);
  ASSERT_EQ(listed.size(), 1u);
  const DeviceListing& d = listed.front();
  EXPECT_EQ(d.serial, options.serial);
  EXPECT_EQ(d.vid, pu::kVendorId);
  EXPECT_EQ(d.pid, pu::kProductId);
  std::string product;
  ASSERT_TRUE(read_string_ascii(*rig, usb::kStringProduct, product));
  EXPECT_FALSE(product.empty());
  EXPECT_EQ(d.product, product);
  EXPECT_EQ(d.firmware_version, "0.1");  // bcdDevice 0x0001: the core's firmware 0.1
  EXPECT_EQ(d.uris, (std::vector<std::string>{"usb://" + options.serial, "hid://" + options.serial}));
  EXPECT_EQ(d.note, "");
  EXPECT_EQ(rig->violations(), std::vector<std::string>{});
}

TEST(UsbE2eUsb, HelloAndDeviceInfoComeBackWithTheBoardsIdentityAndItsStreamCeiling) {
  const RigOptions options;
  auto rig = std::make_shared<BoardRig>(options);
  Probe probe(open_usb(rig, "usb://" + options.serial));
  EXPECT_FALSE(probe.handshake().missing_features) << probe.handshake().message;
  EXPECT_EQ(probe.info().serial, options.serial);
  EXPECT_EQ(probe.info().board, "stm32g474-rig");
  EXPECT_EQ(probe.info().max_stream_rate_Hz, 20000.0);
  EXPECT_EQ(probe.info().control_rate_Hz, 20000.0);
  probe.close();
  EXPECT_EQ(rig->violations(), std::vector<std::string>{});
}

TEST(UsbE2eUsb, AParameterWrittenIsReadBackUnchangedAndTheOthersKept) {
  auto rig = std::make_shared<BoardRig>();
  Probe probe(open_usb(rig, "usb://"));
  Params p = probe.params();
  const Params before = p;
  p.current_clamp_A = 1.25f;
  p.heartbeat_timeout_ms = 750;
  probe.set_params(p);
  const Params after = probe.params();
  EXPECT_EQ(after.current_clamp_A, 1.25f);
  EXPECT_EQ(after.heartbeat_timeout_ms, 750u);
  EXPECT_EQ(after.control_rate_Hz, before.control_rate_Hz);
  EXPECT_EQ(after.travel_max_counts, before.travel_max_counts);
  probe.close();
  EXPECT_EQ(rig->violations(), std::vector<std::string>{});
}

// The throughput question on the whole path: every control tick at 20 kHz, all 11
// channels (499 500 bytes/s on the wire), 0.5 s of it read back through usb:// with every index.
TEST(UsbE2eUsb, EveryTickStreamedAtTwentyKilohertzWithAllChannelsArrivesWithContinuousIndices) {
  auto rig = std::make_shared<BoardRig>();
  Probe probe(open_usb(rig, "usb://"));
  const std::size_t count = 10000;
  const Streamed s = stream(probe, {.rate_Hz = 20000.0, .channels = channel::all,
                                    .batch_samples = 40}, count);
  EXPECT_EQ(probe.stream_info().wire_bytes_per_s, 499500u);
  expect_continuous(s, count, 50e-6);
  const HealthCounters h = probe.health();
  EXPECT_EQ(h.host_rx_rejected, 0u);
  EXPECT_EQ(h.stream_samples_lost + h.isr_queue_overflows + h.tx_frames_dropped, 0u);
  print_rig(*rig, "usb:// 20 kHz, 11 channels");
  probe.close();
  EXPECT_EQ(rig->violations(), std::vector<std::string>{});
}

// At the 40 kHz control rate the core's ceiling is every second tick: the SDK refuses every tick
// (above DeviceInfo's ceiling) before asking, and 20 kHz arrives whole. The stream is configured by
// a session opened after the rate change, so DeviceInfo itself reports 40 kHz (the same session
// would do too: ProbeConnect.AControlRateSetThroughSetParamsIsTheRateTheStreamDecimationComesFrom).
TEST(UsbE2eUsb, AtAFortyKilohertzControlRateEverySecondTickStreamsAndEveryTickIsRefused) {
  auto rig = std::make_shared<BoardRig>();
  {
    Probe setup(open_usb(rig, "usb://"));
    Params p = setup.params();
    p.control_rate_Hz = 40000;
    setup.set_params(p);
  }
  Probe probe(open_usb(rig, "usb://"));
  ASSERT_EQ(probe.info().control_rate_Hz, 40000.0);
  try {
    probe.configure_stream({.rate_Hz = 40000.0, .channels = channel::all, .batch_samples = 40});
    FAIL() << "every tick at 40 kHz was accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "stream rate 40000 Hz is outside (0, 20000] Hz, the device's range");
  }
  const std::size_t count = 4000;
  const Streamed s = stream(probe, {.rate_Hz = 20000.0, .channels = channel::all,
                                    .batch_samples = 40}, count);
  expect_continuous(s, count, 50e-6);
  print_rig(*rig, "usb:// 40 kHz control rate, 20 kHz stream");
  probe.close();
  EXPECT_EQ(rig->violations(), std::vector<std::string>{});
}

// The sequence check above is not vacuous: one bulk IN packet lost on the bus (its 64 bytes
// never reach the SDK) breaks a frame, which the SDK's frame reader rejects and its index check
// reports as a transport gap of whole batches.
TEST(UsbE2eUsb, OneBulkPacketLostOnTheBusShowsAsATransportGapOfWholeBatches) {
  auto rig = std::make_shared<BoardRig>();
  Probe probe(open_usb(rig, "usb://"));
  rig->lose_in_packet(pu::kBulkInEndpoint & 0x0F, 200);
  const Streamed s = stream(probe, {.rate_Hz = 20000.0, .channels = channel::all,
                                    .batch_samples = 40}, 6000);
  ASSERT_FALSE(s.gaps.empty());
  std::uint64_t missing = 0;
  for (const Gap& g : s.gaps) {
    EXPECT_EQ(g.source, GapSource::transport);
    missing += g.count;
  }
  EXPECT_GT(missing, 0u);
  EXPECT_EQ(missing % 40, 0u);  // whole batches: a frame is lost whole or not at all
  EXPECT_GE(probe.health().host_rx_rejected, 1u);
  probe.close();
}

TEST(UsbE2eHid, HelloDeviceInfoAndParametersGoThroughSixtyFourByteReports) {
  const RigOptions options;
  auto rig = std::make_shared<BoardRig>(options);
  Probe probe(open_hid(rig, "hid://" + options.serial));
  EXPECT_EQ(probe.info().serial, options.serial);
  Params p = probe.params();
  p.current_clamp_A = 0.5f;
  probe.set_params(p);
  EXPECT_EQ(probe.params().current_clamp_A, 0.5f);
  probe.close();
  EXPECT_EQ(rig->device_counters().pipe_switches, 0u);  // it answered on HID from the start
  EXPECT_EQ(rig->violations(), std::vector<std::string>{});
}

// HID carries 64 000 bytes/s: all channels at 2 kHz is 49 950 bytes/s (SPEC.md §9.1).
TEST(UsbE2eHid, AllChannelsStreamedAtTwoKilohertzArriveWithContinuousIndices) {
  auto rig = std::make_shared<BoardRig>();
  Probe probe(open_hid(rig, "hid://"));
  const std::size_t count = 1000;
  const Streamed s = stream(probe, {.rate_Hz = 2000.0, .channels = channel::all,
                                    .batch_samples = 40}, count);
  expect_continuous(s, count, 500e-6);
  EXPECT_EQ(probe.health().host_rx_rejected, 0u);
  print_rig(*rig, "hid:// 2 kHz, 11 channels");
  probe.close();
  EXPECT_EQ(rig->violations(), std::vector<std::string>{});
}

TEST(UsbE2eHid, TheSdkRefusesATwentyKilohertzStreamHidCannotCarryBeforeItStarts) {
  auto rig = std::make_shared<BoardRig>();
  Probe probe(open_hid(rig, "hid://"));
  try {
    probe.configure_stream({.rate_Hz = 20000.0, .channels = channel::all, .batch_samples = 40});
    FAIL() << "a 499 500 bytes/s stream was accepted over hid://";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "stream of 24-byte samples at 20000 Hz needs 499500 bytes/s on the wire, but "
              "hid:// carries at most 64000 bytes/s: lower the rate or stream fewer channels");
  }
  probe.close();
}

}  // namespace
}  // namespace palp::usb_e2e
