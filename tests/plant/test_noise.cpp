// SPDX-License-Identifier: Apache-2.0
// The sensors' Gaussian noise (noise.hpp, README.md "Noise"): a pure function of (seed, stream,
// tick); standard normal in its moments, its distribution and its tails; no correlation from
// tick to tick or between streams. Each statistic is taken over 10^6 draws and held to five of
// its standard errors (for a true N(0, 1) the chance of a false failure is below 1e-6 each), so
// these are known-answer checks for the pinned seeds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "palp/plant/noise.hpp"

namespace palp::plant {
namespace {

constexpr int kDraws = 1'000'000;
constexpr double kN = kDraws;

std::vector<double> draws(std::uint64_t seed, std::uint32_t stream, int n = kDraws) {
  std::vector<double> g(static_cast<std::size_t>(n));
  const std::uint64_t key = noise_key(seed, stream);
  for (int k = 0; k < n; ++k) g[static_cast<std::size_t>(k)] = gaussian_at(key, static_cast<std::uint64_t>(k));
  return g;
}

// The plant's streams: current sense, encoder, pressure channels 1..6.
constexpr std::uint32_t kStreams[] = {1, 2, 17, 18, 19, 20, 21, 22};

double normal_tail(double x) { return 0.5 * std::erfc(x / std::sqrt(2.0)); }  // P(g > x)

// sum of a[k] b[k + lag] / n over the overlap (both means ~0, variances ~1)
double correlation(const std::vector<double>& a, const std::vector<double>& b, int lag) {
  double s = 0.0;
  const std::size_t n = a.size() - static_cast<std::size_t>(lag);
  for (std::size_t k = 0; k < n; ++k) s += a[k] * b[k + static_cast<std::size_t>(lag)];
  return s / static_cast<double>(n);
}

TEST(Noise, IsAPureFunctionOfSeedStreamAndTick) {
  // the same numbers whatever was drawn before or in which order
  const double late = gaussian(7, 18, 123456);
  for (int k = 0; k < 1000; ++k) (void)gaussian(7, 18, static_cast<std::uint64_t>(k));
  EXPECT_EQ(gaussian(7, 18, 123456), late);
  EXPECT_EQ(gaussian_at(noise_key(7, 18), 123456), late);
  // pinned: a change of generator shows here first (then tests/sim's reference hashes move)
  EXPECT_EQ(gaussian(1, 1, 0), -0x1.a606781d2451bp-1);
  EXPECT_EQ(gaussian(1, 17, 1000), 0x1.6fa4af0e54378p-6);
  EXPECT_EQ(gaussian(42, 2, 99), 0x1.a673e943c5c9fp+0);
  // another seed, another stream, another tick: other numbers
  EXPECT_NE(gaussian(2, 1, 0), gaussian(1, 1, 0));
  EXPECT_NE(gaussian(1, 2, 0), gaussian(1, 1, 0));
  EXPECT_NE(gaussian(1, 1, 1), gaussian(1, 1, 0));
}

TEST(Noise, EveryStreamHasTheMomentsOfAStandardNormal) {
  for (const std::uint32_t stream : kStreams) {
    const std::vector<double> g = draws(1, stream);
    double m1 = 0, m2 = 0, m3 = 0, m4 = 0;
    for (const double x : g) {
      const double x2 = x * x;
      m1 += x;
      m2 += x2;
      m3 += x2 * x;
      m4 += x2 * x2;
    }
    m1 /= kN, m2 /= kN, m3 /= kN, m4 /= kN;
    // standard errors for N(0, 1): mean 1/sqrt(n), variance sqrt(2/n), skewness sqrt(6/n),
    // kurtosis sqrt(24/n)
    EXPECT_NEAR(m1, 0.0, 5.0 * std::sqrt(1.0 / kN)) << "stream " << stream;
    EXPECT_NEAR(m2, 1.0, 5.0 * std::sqrt(2.0 / kN)) << "stream " << stream;
    EXPECT_NEAR(m3 / std::pow(m2, 1.5), 0.0, 5.0 * std::sqrt(6.0 / kN)) << "stream " << stream;
    EXPECT_NEAR(m4 / (m2 * m2), 3.0, 5.0 * std::sqrt(24.0 / kN)) << "stream " << stream;
  }
}

TEST(Noise, DistributionPassesKolmogorovSmirnovAndItsTailsHaveTheNormalWeight) {
  std::vector<double> g = draws(3, 1);
  // two-sided tail counts, each within five binomial standard errors of n P(|g| > x)
  const double r = ziggurat_tail_start();
  for (const double x : {1.0, 2.0, 3.0, r, 4.0, 4.5}) {
    const double p = 2.0 * normal_tail(x);
    const auto beyond = std::count_if(g.begin(), g.end(), [&](double v) { return std::abs(v) > x; });
    EXPECT_NEAR(static_cast<double>(beyond), kN * p, 5.0 * std::sqrt(kN * p * (1.0 - p)) + 1.0)
        << "|g| > " << x;
  }
  // both signs reach beyond the ziggurat's base (the tail method runs)
  EXPECT_GT(*std::max_element(g.begin(), g.end()), r + 0.3);
  EXPECT_LT(*std::min_element(g.begin(), g.end()), -r - 0.3);
  // Kolmogorov-Smirnov: sqrt(n) D below 1.95 (the 0.1 % critical value)
  std::sort(g.begin(), g.end());
  double d = 0.0;
  for (std::size_t k = 0; k < g.size(); ++k) {
    const double cdf = 1.0 - normal_tail(g[k]);
    d = std::max({d, std::abs(cdf - static_cast<double>(k) / kN),
                  std::abs(cdf - static_cast<double>(k + 1) / kN)});
  }
  EXPECT_LT(std::sqrt(kN) * d, 1.95);
}

TEST(Noise, SuccessiveTicksAreUncorrelated) {
  const std::vector<double> g = draws(1, 17);
  for (const int lag : {1, 2, 3, 8, 20, 100, 1000}) {
    EXPECT_NEAR(correlation(g, g, lag), 0.0, 5.0 / std::sqrt(kN)) << "lag " << lag;
  }
  // nor are the signs and magnitudes of one draw (they come from disjoint bits of its word)
  double s = 0.0;
  for (const double x : g) s += (x > 0 ? 1.0 : -1.0) * (std::abs(x) - std::sqrt(2.0 / M_PI));
  EXPECT_NEAR(s / kN, 0.0, 5.0 * std::sqrt((1.0 - 2.0 / M_PI) / kN));
}

TEST(Noise, StreamsAndSeedsAreIndependentOfEachOther) {
  std::vector<std::vector<double>> g;
  for (const std::uint32_t stream : kStreams) g.push_back(draws(1, stream));
  for (std::size_t a = 0; a < g.size(); ++a) {
    for (std::size_t b = a + 1; b < g.size(); ++b) {
      for (const int lag : {0, 1}) {
        EXPECT_NEAR(correlation(g[a], g[b], lag), 0.0, 5.0 / std::sqrt(kN))
            << "streams " << kStreams[a] << ", " << kStreams[b] << " lag " << lag;
        EXPECT_NEAR(correlation(g[b], g[a], lag), 0.0, 5.0 / std::sqrt(kN))
            << "streams " << kStreams[b] << ", " << kStreams[a] << " lag " << lag;
      }
    }
  }
  // the same stream under neighbouring seeds
  EXPECT_NEAR(correlation(g[0], draws(2, 1), 0), 0.0, 5.0 / std::sqrt(kN));
}

}  // namespace
}  // namespace palp::plant
