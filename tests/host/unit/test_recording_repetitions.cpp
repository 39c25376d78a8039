// SPDX-License-Identifier: Apache-2.0
// split_repetitions_at_current_minima: known answers on synthetic currents. A noisy staircase
// repeated three times gives exactly three repetitions, each starting where the load starts
// again; noise, holds and shallow dips never split.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>

#include "palp/recording.hpp"
#include "test_recording_util.hpp"

using palp::split_repetitions_at_current_minima;

namespace {

/// The repetition every sample belongs to when repetition r starts at starts[r].
std::vector<int> expected_reps(std::size_t n, const std::vector<std::size_t>& starts) {
  std::vector<int> rep(n);
  for (std::size_t k = 0; k < n; ++k)
    rep[k] =
        static_cast<int>(std::upper_bound(starts.begin(), starts.end(), k) - starts.begin()) - 1;
  return rep;
}

/// Where each repetition after the first starts in rep.
std::vector<std::size_t> found_starts(const std::vector<int>& rep) {
  std::vector<std::size_t> starts;
  for (std::size_t k = 1; k < rep.size(); ++k)
    if (rep[k] != rep[k - 1]) starts.push_back(k);
  return starts;
}

}  // namespace

TEST(RecordingRepetitions, NoisyStaircaseThreeTimesSplitsExactlyWhereTheLoadStartsAgain) {
  std::vector<std::size_t> starts;
  const auto i_A = palp_test::staircase(0.1, 50, 3, 0.002, starts);  // 2 mA rms
  EXPECT_EQ(split_repetitions_at_current_minima(i_A), expected_reps(i_A.size(), starts));
}

TEST(RecordingRepetitions, PaperStaircaseOf10mAStepsWithNoiseSplitsIntoExactlyThree) {
  std::vector<std::size_t> starts;
  const auto i_A = palp_test::staircase(0.01, 10, 3, 0.002, starts, 11);  // 15 030 samples
  const std::vector<int> rep = split_repetitions_at_current_minima(i_A);
  const std::vector<std::size_t> found = found_starts(rep);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(rep.front(), 0);
  EXPECT_EQ(rep.back(), 2);
  for (std::size_t r = 0; r < 2; ++r)  // within two 10 mA steps of the true start
    EXPECT_LE(std::abs(static_cast<long>(found[r]) - static_cast<long>(starts[r + 1])), 20)
        << "repetition " << r + 1;
}

TEST(RecordingRepetitions, NoiseFreeTriangleSplitsAtItsMinima) {
  std::vector<double> i_A;  // 0 → 1 → 0 in 100 samples each way, three times, then one sample
  for (int k = 0; k <= 600; ++k) i_A.push_back(1.0 - std::abs((k % 200) - 100) / 100.0);
  const std::vector<int> rep = split_repetitions_at_current_minima(i_A);
  EXPECT_EQ(found_starts(rep), (std::vector<std::size_t>{200, 400}));
  EXPECT_EQ(rep.back(), 2);  // the last minimum, after the last rise, belongs to the last
}

TEST(RecordingRepetitions, HoldWithNoiseIsOneRepetition) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.002);
  std::vector<double> i_A(20000);
  for (double& v : i_A) v = 1.0 + noise(rng);
  const std::vector<int> rep = split_repetitions_at_current_minima(i_A);
  EXPECT_TRUE(std::all_of(rep.begin(), rep.end(), [](int r) { return r == 0; }));
}

TEST(RecordingRepetitions, DipThatDoesNotReturnNearTheStartDoesNotSplit) {
  // 0.5 → 3 → 1.5 → 3 → 0.5 A: the dip to 1.5 A stays above a quarter of the range (1.125 A).
  std::vector<double> i_A;
  const auto ramp = [&](double from, double to) {
    for (int k = 0; k <= 100; ++k) i_A.push_back(from + (to - from) * k / 100.0);
  };
  ramp(0.5, 3.0);
  ramp(3.0, 1.5);
  ramp(1.5, 3.0);
  ramp(3.0, 0.5);
  const std::vector<int> rep = split_repetitions_at_current_minima(i_A);
  EXPECT_TRUE(found_starts(rep).empty());
  ramp(0.5, 3.0);  // a real second repetition
  EXPECT_EQ(found_starts(split_repetitions_at_current_minima(i_A)).size(), 1u);
}

TEST(RecordingRepetitions, FewSamplesAreOneRepetition) {
  EXPECT_TRUE(split_repetitions_at_current_minima({}).empty());
  const std::vector<double> two = {0.5, 3.0};
  EXPECT_EQ(split_repetitions_at_current_minima(two), (std::vector<int>{0, 0}));
}
