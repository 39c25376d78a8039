// SPDX-License-Identifier: Apache-2.0
// Stream requests are checked before anything is sent: rates that do not divide the control
// rate, unknown channels, oversized batches and streams a transport cannot carry are refused
// with the numbers in the message.
#include <gtest/gtest.h>

#include "palp/error.hpp"
#include "palp/protocol/usb.hpp"
#include "probe/stream_check.hpp"

namespace {

using palp::StreamSettings;
using palp::detail::check_stream;
namespace channel = palp::channel;

std::string refusal(const StreamSettings& s, std::uint32_t bytes_per_s = 1'000'000) {
  try {
    check_stream(s, 20000, 10000, bytes_per_s, "hid://PALP-7");
  } catch (const palp::ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(StreamCheck, AValidRequestBecomesDecimationAndAboutTwentyFiveBatchesASecond) {
  const auto c = check_stream({.rate_Hz = 1000, .channels = channel::all, .batch_samples = 0},
                              20000, 10000, 1'000'000, "sim://x:1");
  EXPECT_EQ(c.decimation, 20);
  EXPECT_EQ(c.batch_samples, 40);
  EXPECT_EQ(c.channels, channel::all);
}

TEST(StreamCheck, AllChannelsAt10kHzDoNotFitHidAndTheMessageGivesBothByteRates) {
  EXPECT_EQ(refusal({.rate_Hz = 10000, .channels = channel::all, .batch_samples = 0},
                    palp::proto::usb::kHidBytesPerS),
            "stream of 24-byte samples at 10000 Hz needs 249750 bytes/s on the wire, but "
            "hid://PALP-7 carries at most 64000 bytes/s: lower the rate or stream fewer channels");
}

TEST(StreamCheck, CurrentAndEncoderAt5kHzFitHid) {
  EXPECT_EQ(refusal({.rate_Hz = 5000, .channels = channel::i_meas | channel::encoder,
                     .batch_samples = 0},
                    palp::proto::usb::kHidBytesPerS),
            "accepted");
}

TEST(StreamCheck, RatesOutsideTheRangeOrNotDividingTheControlRateAreRefusedWithNeighbours) {
  EXPECT_EQ(refusal({.rate_Hz = 3000, .channels = channel::all, .batch_samples = 0}),
            "stream rate 3000 Hz does not divide the control rate 20000 Hz (nearest: 2857.14 Hz "
            "or 3333.33 Hz)");
  EXPECT_EQ(refusal({.rate_Hz = 20000, .channels = channel::all, .batch_samples = 0}),
            "stream rate 20000 Hz is outside (0, 10000] Hz, the device's range");
  EXPECT_EQ(refusal({.rate_Hz = 0, .channels = channel::all, .batch_samples = 0}),
            "stream rate 0 Hz is outside (0, 10000] Hz, the device's range");
}

TEST(StreamCheck, NoChannelsUnknownChannelsAndOversizedBatchesAreRefused) {
  EXPECT_EQ(refusal({.rate_Hz = 1000, .channels = 0, .batch_samples = 0}),
            "stream channels 0x0000: choose one or more of the 11 channel bits (palp::channel)");
  EXPECT_EQ(refusal({.rate_Hz = 1000, .channels = 0x0800, .batch_samples = 0}),
            "stream channels 0x0800: choose one or more of the 11 channel bits (palp::channel)");
  EXPECT_EQ(refusal({.rate_Hz = 1000, .channels = channel::all, .batch_samples = 41}),
            "stream batch of 41 samples: at most 40 samples of 24 bytes fit one batch");
}

}  // namespace
