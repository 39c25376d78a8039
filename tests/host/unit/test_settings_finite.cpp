// SPDX-License-Identifier: Apache-2.0
// Every SDK entry point's settings refuse NaN and infinities by the field's name (issue 17, item
// 3, the SDK half): a range check alone lets NaN through, as every comparison with it is false.
// One test per settings struct, each field set to NaN, +inf and -inf in turn; and a request whose
// float field is not finite is refused before anything is sent.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "palp/error.hpp"
#include "palp/identification.hpp"
#include "palp/indent.hpp"
#include "palp/rig.hpp"
#include "probe/session.hpp"

namespace {

using testing::HasSubstr;

const double kBad[] = {std::nan(""), std::numeric_limits<double>::infinity(),
                       -std::numeric_limits<double>::infinity()};
const char* kBadText[] = {"nan", "inf", "-inf"};

/// For each named field: the struct with it set to each non-finite value, checked by validate().
template <class S>
void expect_named(const S& good, const std::string& who,
                  const std::vector<std::pair<std::string, std::function<double&(S&)>>>& fields) {
  EXPECT_NO_THROW(good.validate());
  for (const auto& [name, field] : fields)
    for (int k = 0; k < 3; ++k) {
      S s = good;
      field(s) = kBad[k];
      try {
        s.validate();
        ADD_FAILURE() << name << " = " << kBadText[k] << " passed";
      } catch (const palp::ConfigError& e) {
        EXPECT_EQ(std::string(e.what()), who + ": " + name + " is " + kBadText[k] + ", not a finite number");
      }
    }
}

TEST(SettingsFinite, IndentationSettingsNameEveryNonFiniteFieldAnalysisIncluded) {
  palp::IndentationSettings s;
  s.analysis.thickness = palp::analysis::Thickness{5e-3, palp::analysis::Bonding::bonded};
  s.analysis.force_noise_N = 0.01;
  using S = palp::IndentationSettings;
  expect_named<S>(s, "indentation settings",
                  {{"start_A", [](S& x) -> double& { return x.start_A; }},
                   {"stop_A", [](S& x) -> double& { return x.stop_A; }},
                   {"step_A", [](S& x) -> double& { return x.step_A; }},
                   {"dwell_s", [](S& x) -> double& { return x.dwell_s; }},
                   {"displacement_limit_m", [](S& x) -> double& { return x.displacement_limit_m; }},
                   {"stream_rate_Hz", [](S& x) -> double& { return x.stream_rate_Hz; }},
                   {"zero_pressure_s", [](S& x) -> double& { return x.zero_pressure_s; }},
                   {"settle_s", [](S& x) -> double& { return x.settle_s; }},
                   {"analysis.force_constant_N_per_A", [](S& x) -> double& { return x.analysis.force_constant_N_per_A; }},
                   {"analysis.contact_current_A", [](S& x) -> double& { return x.analysis.contact_current_A; }},
                   {"analysis.spring_N_per_m", [](S& x) -> double& { return x.analysis.spring_N_per_m; }},
                   {"analysis.tip_radius_m", [](S& x) -> double& { return x.analysis.tip_radius_m; }},
                   {"analysis.poisson", [](S& x) -> double& { return x.analysis.poisson; }},
                   {"analysis.bias_current_A", [](S& x) -> double& { return x.analysis.bias_current_A; }},
                   {"analysis.thickness.thickness_m", [](S& x) -> double& { return x.analysis.thickness->thickness_m; }},
                   {"analysis.window_lo_m", [](S& x) -> double& { return x.analysis.window_lo_m; }},
                   {"analysis.window_hi_m", [](S& x) -> double& { return x.analysis.window_hi_m; }},
                   {"analysis.local_half_width_m", [](S& x) -> double& { return x.analysis.local_half_width_m; }},
                   {"analysis.force_noise_N", [](S& x) -> double& { return *x.analysis.force_noise_N; }},
                   {"analysis.tangent_depths_m[2]", [](S& x) -> double& { return x.analysis.tangent_depths_m[2]; }}});
}

TEST(SettingsFinite, IdentificationSettingsNameEveryNonFiniteField) {
  using S = palp::IdentificationSettings;
  for (const auto preset : {palp::IdentificationPreset::contact_stepped, palp::IdentificationPreset::contact_multisine,
                            palp::IdentificationPreset::contact_multisine_fast}) {
    const S s = S::preset(preset);
    expect_named<S>(s, "identification settings",
                    {{"bias_A", [](S& x) -> double& { return x.bias_A; }},
                     {"amplitude_A", [](S& x) -> double& { return x.amplitude_A; }},
                     {"f_lo_Hz", [](S& x) -> double& { return x.f_lo_Hz; }},
                     {"f_hi_Hz", [](S& x) -> double& { return x.f_hi_Hz; }},
                     {"step_Hz", [](S& x) -> double& { return x.step_Hz; }},
                     {"settle_min_s", [](S& x) -> double& { return x.settle_min_s; }},
                     {"fundamental_Hz", [](S& x) -> double& { return x.fundamental_Hz; }},
                     {"stream_rate_Hz", [](S& x) -> double& { return x.stream_rate_Hz; }},
                     {"settle_s", [](S& x) -> double& { return x.settle_s; }},
                     {"contact_current_A", [](S& x) -> double& { return x.contact_current_A; }},
                     {"max_excursion_m", [](S& x) -> double& { return x.max_excursion_m; }},
                     {"frf.force_constant_N_per_A", [](S& x) -> double& { return x.frf.force_constant_N_per_A; }},
                     {"instrument.m_v_kg", [](S& x) -> double& { return x.instrument.m_v_kg; }},
                     {"fit.adequate_cost", [](S& x) -> double& { return x.fit.adequate_cost; }}});
  }
}

TEST(SettingsFinite, KfCalibrationSettingsNameEveryNonFiniteField) {
  using S = palp::KfCalibrationSettings;
  expect_named<S>(S{}, "K_f calibration settings",
                  {{"start_A", [](S& x) -> double& { return x.start_A; }},
                   {"stop_A", [](S& x) -> double& { return x.stop_A; }},
                   {"step_A", [](S& x) -> double& { return x.step_A; }},
                   {"dwell_s", [](S& x) -> double& { return x.dwell_s; }},
                   {"settled_fraction", [](S& x) -> double& { return x.settled_fraction; }},
                   {"k_v_N_per_m", [](S& x) -> double& { return x.k_v_N_per_m; }},
                   {"stream_rate_Hz", [](S& x) -> double& { return x.stream_rate_Hz; }},
                   {"anchor.stroke_m", [](S& x) -> double& { return x.anchor->stroke_m; }},
                   {"anchor.kf_N_per_A", [](S& x) -> double& { return x.anchor->kf_N_per_A; }}});
}

palp::Rig good_rig() {
  palp::Rig r;
  r.robot_uri = "modbus://127.0.0.1:30005";
  r.probe_uri = "sim://127.0.0.1:7070";
  r.work_object = palp::WorkObject{"pad", palp::Pose{0.6, 0, 0.3, 0, 0, 3.14159}};
  return r;
}

TEST(SettingsFinite, RigNamesEveryNonFiniteField) {
  using S = palp::Rig;
  expect_named<S>(good_rig(), "rig",
                  {{"safe_height_m", [](S& x) -> double& { return x.safe_height_m; }},
                   {"approach_speed_m_per_s", [](S& x) -> double& { return x.approach_speed_m_per_s; }},
                   {"travel_speed_m_per_s", [](S& x) -> double& { return x.travel_speed_m_per_s; }},
                   {"contact_threshold_m", [](S& x) -> double& { return x.contact_threshold_m; }},
                   {"watch_current_A", [](S& x) -> double& { return x.watch_current_A; }},
                   {"max_approach_m", [](S& x) -> double& { return x.max_approach_m; }},
                   {"tip_radius_m", [](S& x) -> double& { return x.tip_radius_m; }},
                   {"tool_tcp.z_m", [](S& x) -> double& { return x.tool_tcp.z_m; }},
                   {"work_object.pose.c_rad", [](S& x) -> double& { return x.work_object->pose.c_rad; }}});
  palp::Rig out_of_range = good_rig();
  out_of_range.safe_height_m = -1e-3;
  EXPECT_THROW(out_of_range.validate(), palp::ConfigError);
}

TEST(SettingsFinite, PlanNamesEveryNonFiniteField) {
  using S = palp::Plan;
  S p;
  p.name = "pad";
  p.contact_E_star_Pa = 3.3e6;
  p.approach_speed_m_per_s = 1e-3;
  expect_named<S>(p, "plan pad",
                  {{"grid.x0_m", [](S& x) -> double& { return x.grid.x0_m; }},
                   {"grid.y0_m", [](S& x) -> double& { return x.grid.y0_m; }},
                   {"grid.pitch_x_m", [](S& x) -> double& { return x.grid.pitch_x_m; }},
                   {"grid.pitch_y_m", [](S& x) -> double& { return x.grid.pitch_y_m; }},
                   {"contact_E_star_Pa", [](S& x) -> double& { return *x.contact_E_star_Pa; }},
                   {"approach_speed_m_per_s", [](S& x) -> double& { return *x.approach_speed_m_per_s; }}});
}

TEST(SettingsFinite, ARequestWithANonFiniteFieldIsRefusedByNameBeforeSending) {
  palp::HoldProgram h;
  h.current_A = std::nanf("");
  try {
    palp::detail::require_finite_fields(h);
    FAIL() << "no ConfigError";
  } catch (const palp::ConfigError& e) {
    EXPECT_STREQ(e.what(), "LoadHold: current_A is nan, not a finite number; nothing was sent");
  }
  palp::Calibration c;
  c.pressure_gain[3] = -std::numeric_limits<float>::infinity();
  try {
    palp::detail::require_finite_fields(c);
    FAIL() << "no ConfigError";
  } catch (const palp::ConfigError& e) {
    EXPECT_STREQ(e.what(), "Calibration: pressure_gain[3] is -inf, not a finite number; nothing was sent");
  }
  EXPECT_NO_THROW(palp::detail::require_finite_fields(palp::RampProgram{}));
}

}  // namespace
