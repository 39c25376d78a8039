// SPDX-License-Identifier: Apache-2.0
// Force-constant calibration (kf_calibration.hpp) against a synthetic free-air staircase: the
// plant's K_f(s) table (palp::plant::default_kf_table), k_v 43.9 N/m, the coil settling on every
// stair at K_f(s) i - c = k_v s; the stream decimated 20 from 20 kHz, the ramp starting between
// two samples.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "palp/analysis/kf_calibration.hpp"
#include "palp/error.hpp"
#include "palp/plant/config.hpp"
#include "palp/plant/force_constant.hpp"
#include "palp/protocol/program_schedule.hpp"
#include "palp/protocol/stream.hpp"

namespace {

namespace an = palp::analysis;
namespace proto = palp::proto;
using ::testing::HasSubstr;

constexpr std::uint32_t kKfRate = 20000;
constexpr std::int64_t kKfDecimation = 20;
constexpr double kKv = 43.9;
constexpr double kC = 0.3615;  // N: the balance's constant (preload and gravity)
constexpr double kOrigin = 0.004;  // the recording's z of the stroke origin, m

const palp::plant::ForceConstantTable& plant_kf() {
  static const palp::plant::ForceConstantTable t(palp::plant::default_kf_table());
  return t;
}

/// The static stroke at current i: K_f(s) i - c = k_v s (bisection; unique for these currents).
double balance_stroke(double i) {
  double lo = -0.01, hi = 0.05;
  for (int it = 0; it < 80; ++it) {
    const double mid = 0.5 * (lo + hi);
    (plant_kf().at(mid) * i - kC > kKv * mid ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// 0.12 -> 0.64 A by 5 mA (105 levels), 50 ms per stair, both ways: s from ~0.5 to ~33 mm.
proto::LoadRamp calibration_ramp() {
  proto::LoadRamp m;
  m.start_A = 0.12f;
  m.stop_A = 0.64f;
  m.step_A = 0.005f;
  m.dwell_s = 0.05f;
  m.repetitions = 1;
  m.unload = 1;
  return m;
}

struct StairSynth {
  std::int64_t stream_start_tick = 4321 * kKfDecimation;
  std::int64_t program_offset_ticks = 6007;  // not on a sample
  double tau_s = 0.002;                      // the coil settles with this time constant
  double noise_i_A = 0, noise_z_m = 0;
  unsigned seed = 7;
};

palp::Recording ramp_recording(const proto::LoadRamp& m, const StairSynth& s) {
  const proto::RampTiming t = proto::ramp_timing(m, kKfRate);
  const double step = m.step_A;
  std::mt19937 rng(s.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  palp::Recording rec;
  const auto total = static_cast<std::int64_t>(t.total_ticks);
  double z_prev = balance_stroke(m.start_A);  // held at start_A before the ramp
  std::uint32_t level_prev = 0;
  std::int64_t changed = 0;  // program tick of the last level change
  for (std::int64_t u = 0; u < s.program_offset_ticks + total + 4000; u += kKfDecimation) {
    const std::int64_t k = u - s.program_offset_ticks;
    const std::uint32_t level =
        k >= 0 && k < total ? proto::ramp_level_at(t, static_cast<std::uint64_t>(k)) : 0;
    const double i = m.start_A + step * level;
    if (level != level_prev) {  // the level changed since the last sample: at its stair's start
      z_prev = balance_stroke(m.start_A + step * level_prev);
      changed = k - (k % t.dwell_ticks);
      level_prev = level;
    }
    const double target = balance_stroke(i);
    const double z = k <= changed ? target
                                  : target + (z_prev - target) *
                                                 std::exp(-static_cast<double>(k - changed) /
                                                          (kKfRate * s.tau_s));
    palp::RecordingRow row;
    row.t_s = static_cast<double>((s.stream_start_tick + u) * 1'000'000 / kKfRate) / 1e6;
    row.i_cmd_A = std::round(i / proto::kCurrentLsb_A) * proto::kCurrentLsb_A;
    row.i_A = i + s.noise_i_A * normal(rng);
    row.z_mm = (kOrigin + z + s.noise_z_m * normal(rng)) * 1e3;
    rec.append(row);
  }
  return rec;
}

TEST(KfStaticPoints, EveryStairGivesItsBalanceFromTheRampsSchedule) {
  const proto::LoadRamp m = calibration_ramp();
  const auto points = an::kf_static_points(ramp_recording(m, StairSynth{}), m, kKfRate, kOrigin);
  ASSERT_EQ(points.size(), 209u);  // 105 up, 104 down
  for (std::size_t q = 0; q < points.size(); ++q) {
    const std::uint32_t level = q < 105 ? static_cast<std::uint32_t>(q)
                                        : static_cast<std::uint32_t>(208 - q);
    const double i = m.start_A + static_cast<double>(m.step_A) * level;
    EXPECT_DOUBLE_EQ(points[q].i_A, i) << q;
    EXPECT_NEAR(points[q].stroke_m, balance_stroke(i), 1e-9) << q;  // the transient is over
    EXPECT_EQ(points[q].samples, 25u) << q;  // the last half of 50 samples
  }
  EXPECT_LT(points.front().stroke_m, 0.001);
  EXPECT_GT(points[104].stroke_m, 0.032);
}

TEST(KfStaticPoints, ATruncatedRecordingIsAConfigErrorNamingTheTimes) {
  const proto::LoadRamp m = calibration_ramp();
  const StairSynth s;
  palp::Recording whole = ramp_recording(m, s), rec;
  for (std::size_t k = 0; k < 5000; ++k)
    rec.append({.t_s = whole.t_s[k], .i_cmd_A = (*whole.i_cmd_A)[k], .i_A = whole.i_A[k],
                .z_mm = whole.z_mm[k]});
  // stream from tick 86420 (4.321 s), the ramp 6007 ticks later (4.62135 s), 209 x 50 ms
  try {
    an::kf_static_points(rec, m, kKfRate, kOrigin);
    FAIL();
  } catch (const palp::ConfigError& e) {
    // the start is known to a sample interval: [4.62105, 4.62200] s, the earliest named
    EXPECT_STREQ(e.what(), "kf_static_points: the recording ends at 9.320000 s, before the ramp "
                           "does (15.071050 s; it started at 4.621050 s)");
  }
}

TEST(FitKfTable, RecoversThePlantsTableAtItsNodesWithNoise) {
  const proto::LoadRamp m = calibration_ramp();
  StairSynth s;
  s.noise_i_A = 2e-3;  // the plant's current-sense noise, averaged over 25 samples
  s.noise_z_m = 1e-6;
  const auto points = an::kf_static_points(ramp_recording(m, s), m, kKfRate, kOrigin);
  const std::vector<double> nodes = {0.0, 0.017, 0.0235, 0.034};  // the plant's
  const an::KfCalibration c = an::fit_kf_table(points, kKv, nodes);
  ASSERT_EQ(c.kf_N_per_A.size(), 4u);
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    const double truth = plant_kf().at(nodes[j]);
    EXPECT_NEAR(c.kf_N_per_A[j], truth, 0.005 * truth) << j;
    EXPECT_GT(c.kf_se_N_per_A[j], 0.0);
    EXPECT_LT(std::abs(c.kf_N_per_A[j] - truth), 4.5 * c.kf_se_N_per_A[j]) << j;
  }
  EXPECT_NEAR(c.c_N, kC, 0.01);
  EXPECT_EQ(c.warning, "");  // four nodes on the table's own kinks hold c
  EXPECT_EQ(c.points, 209u);
  EXPECT_DOUBLE_EQ(c.k_v_N_per_m, kKv);
  EXPECT_GT(c.residual_rms_N, 0.0);
  EXPECT_LT(c.residual_rms_N, 2e-3);
}

TEST(FitKfTable, NoiseFreeIsExactAndTheSlopeIsRecoveredWhereKvDsDiIsBiased) {
  const proto::LoadRamp m = calibration_ramp();
  const auto points = an::kf_static_points(ramp_recording(m, StairSynth{}), m, kKfRate, kOrigin);
  const std::vector<double> nodes = {0.0, 0.017, 0.0235, 0.034};
  const an::KfCalibration c = an::fit_kf_table(points, kKv, nodes);
  for (std::size_t j = 0; j < nodes.size(); ++j)
    EXPECT_NEAR(c.kf_N_per_A[j], plant_kf().at(nodes[j]), 1e-7) << j;
  EXPECT_NEAR(c.c_N, kC, 1e-7);
  // at ~10 mm K_f climbs 0.032 N/A per mm: the local k_v ds/di is off by i dK_f/ds ds/di
  std::size_t q = 0;
  while (points[q].stroke_m < 0.010) ++q;
  const double naive = kKv * (points[q + 1].stroke_m - points[q - 1].stroke_m) /
                       (points[q + 1].i_A - points[q - 1].i_A);
  const double truth = plant_kf().at(points[q].stroke_m);
  EXPECT_GT(std::abs(naive - truth), 0.05 * truth);  // biased by > 5 %
  const double w = points[q].stroke_m / 0.017;       // the fitted table there
  EXPECT_NEAR((1 - w) * c.kf_N_per_A[0] + w * c.kf_N_per_A[1], truth, 1e-6 * truth);
}

TEST(FitKfTable, WithManyNodesOnlyAnAnchorFixesKfAndTheUnanchoredFitSaysSo) {
  // every constant c has its exact K_f = (k_v s + c) / i(s): with 16 nodes the unanchored fit is
  // nearly singular; the anchor (the paper's 2.918 N/A, in the table's flat part) fixes it
  const proto::LoadRamp m = calibration_ramp();
  StairSynth s;
  s.noise_i_A = 2e-3;
  s.noise_z_m = 1e-6;
  const auto points = an::kf_static_points(ramp_recording(m, s), m, kKfRate, kOrigin);
  const std::vector<double> nodes = an::kf_nodes_for(points);
  ASSERT_EQ(nodes.size(), 16u);
  const an::KfCalibration loose = an::fit_kf_table(points, kKv, nodes);
  EXPECT_THAT(loose.warning, HasSubstr("K_f is poorly determined: the constant c has a standard "
                                       "error of "));
  EXPECT_GT(loose.c_se_N, 0.005);
  const an::KfCalibration c = an::fit_kf_table(points, kKv, nodes, an::KfAnchor{0.028, 2.918});
  EXPECT_EQ(c.warning, "");
  EXPECT_NEAR(c.c_N, kC, 0.002);
  EXPECT_LT(c.c_se_N, 0.002);
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    const double truth = plant_kf().at(nodes[j]);
    // the nodes do not sit on the table's kinks at 17 and 23.5 mm: within 2 % everywhere
    EXPECT_NEAR(c.kf_N_per_A[j], truth, 0.02 * truth) << nodes[j];
  }
  const double w = (0.028 - nodes[12]) / (nodes[13] - nodes[12]);  // the anchor holds exactly
  ASSERT_TRUE(nodes[12] <= 0.028 && 0.028 <= nodes[13]);
  EXPECT_NEAR((1 - w) * c.kf_N_per_A[12] + w * c.kf_N_per_A[13], 2.918, 1e-12);
}

TEST(KfNodesFor, EvenlySpacedAtMostMaxNodesWithTwoPointsBetweenNeighbours) {
  std::vector<an::KfStaticPoint> points;
  for (int k = 0; k <= 40; ++k) points.push_back({.stroke_m = 0.001 + 0.0005 * k, .i_A = 0.1});
  const std::vector<double> sixteen = an::kf_nodes_for(points);
  ASSERT_EQ(sixteen.size(), 16u);
  EXPECT_DOUBLE_EQ(sixteen.front(), 0.001);
  EXPECT_DOUBLE_EQ(sixteen.back(), 0.021);
  EXPECT_NEAR(sixteen[1] - sixteen[0], 0.02 / 15, 1e-15);
  // 9 points over 4 mm: 6 nodes 0.8 mm apart would leave one point in [2.6, 3.4) mm
  const std::vector<an::KfStaticPoint> nine(points.begin(), points.begin() + 9);
  const std::vector<double> nodes = an::kf_nodes_for(nine);
  ASSERT_EQ(nodes.size(), 5u);
  EXPECT_NEAR(nodes[1], 0.002, 1e-15);
  // 5 points: at most 2 nodes (the fit needs two points more than nodes + 1 unknowns)
  EXPECT_EQ(an::kf_nodes_for(std::span(points).first(5)).size(), 2u);
  EXPECT_EQ(an::kf_nodes_for(points, 3).size(), 3u);
}

TEST(FitKfTable, BadInputIsAConfigErrorWithExactText) {
  std::vector<an::KfStaticPoint> points;
  for (int k = 0; k < 10; ++k)
    points.push_back({.stroke_m = 0.001 * k, .i_A = 0.2 + 0.01 * k});
  const std::vector<double> nodes = {0.0, 0.004, 0.009};
  auto text = [&](double kv, std::vector<double> n, std::size_t count) {
    try {
      an::fit_kf_table(std::span(points).first(count), kv, n);
    } catch (const palp::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(text(0.0, nodes, 10), "fit_kf_table: k_v must be > 0 (got 0 N/m)");
  EXPECT_EQ(text(kKv, {0.0, 0.009, 0.004}, 10), "fit_kf_table: the nodes must increase (node 2)");
  EXPECT_EQ(text(kKv, nodes, 5), "fit_kf_table: 5 points for 4 unknowns (need at least 6)");
  try {
    an::fit_kf_table(points, kKv, nodes, an::KfAnchor{0.004, 0.0});
    FAIL();
  } catch (const palp::ConfigError& e) {
    EXPECT_STREQ(e.what(), "fit_kf_table: the anchor needs a finite stroke and a finite K_f > 0");
  }
  EXPECT_EQ(text(kKv, {0.0, 0.0041, 0.0042, 0.0043, 0.009}, 10),
            "fit_kf_table: no point between the neighbours of the node at 4.200 mm: its K_f "
            "cannot be identified");
}

}  // namespace
