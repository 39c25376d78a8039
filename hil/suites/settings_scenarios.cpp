// SPDX-License-Identifier: Apache-2.0
// The device's settings: parameters and calibration set, read back exactly, and put back. What
// each scenario proves is in README.md.
#include <gtest/gtest.h>

#include <cstdio>

#include "bench.hpp"

namespace palp::hil {
namespace {

/// a, or b when the device already holds a: the changed value always differs from the old one.
template <class T>
T other_than(T old, T a, T b) {
  return old == a ? b : a;
}

using Parameters = Scenario;
TEST_F(Parameters, SixChangedParametersReadBackExactlyAndTheOriginalsReadBackAfterTheRestore) {
  const Params saved = saved_params();
  Params changed = saved;
  // values a float holds exactly, inside every range and within any bench's limits
  changed.current_clamp_A = other_than(saved.current_clamp_A, 2.5f, 2.25f);
  changed.i2t_tau_s = other_than(saved.i2t_tau_s, 96.0f, 112.0f);
  changed.heartbeat_timeout_ms = other_than<std::uint32_t>(saved.heartbeat_timeout_ms, 750, 800);
  changed.travel_min_counts = saved.travel_min_counts - 1;  // a wider window: trips nothing
  changed.travel_max_counts = saved.travel_max_counts + 1;
  changed.contact_output_hold_ms =
      other_than<std::uint16_t>(saved.contact_output_hold_ms, 150, 200);
  ASSERT_LE(changed.current_clamp_A, probe().info().max_current_A);
  probe().set_params(changed);
  EXPECT_EQ(field_differences(probe().params(), changed), "");
  probe().set_params(saved);
  EXPECT_EQ(field_differences(probe().params(), saved), "");
  EXPECT_EQ(probe().fault().reason, proto::FaultReason::none);
}

/// Calibration scenarios change the device's flash: TearDown writes the calibration found back
/// (RAM and flash) whenever the scenario ended without doing so itself.
class CalibrationBlock : public Scenario {
 protected:
  void SetUp() override {
    Scenario::SetUp();
    if (!HasFatalFailure() && !IsSkipped()) original_ = probe().calibration();
  }
  void TearDown() override {
    if (dirty_) {
      try {
        disconnect();  // a scenario that failed half-way may have left anything: start afresh
        connect();
        probe().set_calibration(*original_);
        probe().commit_calibration();
      } catch (const Error& e) {
        ADD_FAILURE() << "could not put the calibration back: " << e.what();
      }
    }
    Scenario::TearDown();
  }
  std::optional<Calibration> original_;
  bool dirty_ = false;
};

TEST_F(CalibrationBlock,
       ASetCalibrationReadsBackExactlyBeforeAndAfterCommitAndTheOriginalIsRestored) {
  const Calibration original = *original_;
  Calibration changed = original;
  // values a float holds exactly, inside every catalogue range and the device's own checks
  changed.current_offset_A = other_than(original.current_offset_A, 0.0078125f, 0.015625f);
  changed.current_gain = other_than(original.current_gain, 1.0078125f, 0.9921875f);
  for (std::size_t k = 0; k < changed.pressure_offset_Pa.size(); ++k) {
    const float step = 0.5f * static_cast<float>(k + 1);
    changed.pressure_offset_Pa[k] = other_than(original.pressure_offset_Pa[k], step, -step);
    changed.pressure_gain[k] =
        other_than(original.pressure_gain[k], 1.0f + step / 8, 1.0f - step / 16);
  }
  changed.spring_k_N_per_m = other_than(original.spring_k_N_per_m, 44.0f, 43.5f);
  ASSERT_NE(field_differences(changed, original), "");

  dirty_ = true;
  probe().set_calibration(changed);
  EXPECT_EQ(field_differences(probe().calibration(), changed), "") << "set, in RAM";
  probe().commit_calibration();
  EXPECT_EQ(field_differences(probe().calibration(), changed), "") << "committed";
  probe().set_calibration(original);
  EXPECT_EQ(field_differences(probe().calibration(), original), "") << "the original, in RAM";
  probe().commit_calibration();
  dirty_ = false;
  EXPECT_EQ(field_differences(probe().calibration(), original), "") << "the original, committed";
  std::printf("[  FIGURES ] calibration_flash capability: %s\n",
              probe().info().has(proto::Capability::calibration_flash) ? "yes" : "no");
}

}  // namespace
}  // namespace palp::hil
