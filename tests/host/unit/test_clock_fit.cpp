// SPDX-License-Identifier: Apache-2.0
// The device-to-host clock fit on synthetic round trips with a known offset and drift, queueing
// delays that only ever add latency, and a rate that changes part-way.
#include <gtest/gtest.h>

#include <random>

#include "probe/clock_fit.hpp"

namespace {

using palp::detail::ClockFit;

/// host = offset + rate * device; a round trip sent at host time h takes 2*base + extra.
void feed(ClockFit& f, double offset, double rate, double device0, int n, std::mt19937& rng,
          double spacing_s = 0.2) {
  std::exponential_distribution<double> queueing(1.0 / 0.0002);  // mean 0.2 ms extra, sometimes much more
  for (int k = 0; k < n; ++k) {
    const double device = device0 + k * spacing_s;
    const double host_at_device = offset + rate * device;
    const double out = 0.0001 + queueing(rng) * 0.5, back = 0.0001 + queueing(rng) * 0.5;
    f.add(host_at_device - out, device, host_at_device + back);
  }
}

TEST(ClockFit, RecoversOffsetAndDriftDespiteQueueingDelays) {
  std::mt19937 rng(7);
  ClockFit f;
  feed(f, 1234.5, 1.0 + 50e-6, 10.0, 32, rng);  // 50 ppm fast host
  const auto m = f.mapping();
  EXPECT_NEAR(m.drift, 50e-6, 20e-6);
  EXPECT_NEAR(m.to_host_s(16.0), 1234.5 + (1.0 + 50e-6) * 16.0, 0.0005);
}

TEST(ClockFit, OnePointGivesAnOffsetAndNoDrift) {
  ClockFit f;
  f.add(10.0, 2.0, 10.002);
  EXPECT_DOUBLE_EQ(f.mapping().drift, 0.0);
  EXPECT_NEAR(f.mapping().to_host_s(2.0), 10.001, 1e-12);
}

TEST(ClockFit, ARateChangeRestartsTheFitAndItConvergesToTheNewRate) {
  std::mt19937 rng(3);
  ClockFit f;
  feed(f, 0.0, 1.0, 0.0, 32, rng);
  // the device now runs twice as fast as the host (a simulator paced at 2x)
  const double device_now = 31 * 0.2;
  const double host_now = device_now;
  feed(f, host_now - 0.5 * device_now, 0.5, device_now + 0.4, 20, rng, 0.4);
  EXPECT_GE(f.restarts(), 1u);
  EXPECT_NEAR(f.mapping().drift, -0.5, 0.01);
}

}  // namespace
