// SPDX-License-Identifier: Apache-2.0
// A dynamic map's point values (map_dynamic.hpp) from a synthetic identification with known
// answers: a Kelvin-Voigt contact (k_o + j w b_o) on the instrument (m_v, b_v, k_v), and
// map.json's keys for them.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <nlohmann/json.hpp>

#include "palp/analysis/second_order.hpp"
#include "palp/error.hpp"
#include "palp/map.hpp"

namespace {

namespace an = palp::analysis;

constexpr double kMv = 0.1609, kBv = 1.379, kKv = 43.9;  // the instrument (paper §IV-B)
constexpr double kKo = 3000.0, kBo = 4.0;                // the contact, N/m and N s/m
constexpr double kDelta0 = 0.8e-3, kTip = 2.5e-3;        // m
constexpr double kRelNoise = 1e-3;                       // sigma = 1e-3 |G| per line

/// An analysed identification of the Kelvin-Voigt contact over 2-40 Hz every 0.2 Hz.
palp::IdentificationRun kelvin_voigt_run() {
  palp::IdentificationRun run;
  run.settings.instrument = {kMv, kBv, kKv};
  an::Frf frf;
  frf.method = "multisine";
  for (double f = 2.0; f <= 40.0 + 1e-9; f += 0.2) {
    const double w = 2 * std::numbers::pi * f;
    an::FrfLine l;
    l.f_Hz = f;
    l.G_m_per_N = 1.0 / std::complex<double>(kKv + kKo - kMv * w * w, (kBv + kBo) * w);
    l.sigma_m_per_N = kRelNoise * std::abs(l.G_m_per_N);
    frf.lines.push_back(l);
  }
  run.fit = an::fit_second_order(frf.lines);
  run.frf = frf;
  return run;
}

an::IndentationResult indentation_at_bias() {
  an::IndentationResult r;
  r.k_tangent_at_delta0_N_per_m = an::Value::of(kKo);
  r.delta0_m = an::Value::of(kDelta0);
  return r;
}

TEST(MapDynamic, KelvinVoigtContactGivesTheInstrumentsMassItsDampingAndTheModuliOfKoAndBo) {
  const palp::IdentificationRun run = kelvin_voigt_run();
  const an::IndentationResult ind = indentation_at_bias();
  an::IndentationParams params;
  params.tip_radius_m = kTip;
  const palp::DynamicPoint d = palp::dynamic_point_of(run, &ind, params);
  ASSERT_TRUE(d.omega_n_rad_per_s && d.zeta && d.m_eff_kg && d.b_o_N_s_per_m && d.E_storage_Pa &&
              d.E_loss_Pa)
      << d.reason;
  const double k = kKv + kKo, b = kBv + kBo;
  EXPECT_NEAR(*d.omega_n_rad_per_s, std::sqrt(k / kMv), 1e-6 * std::sqrt(k / kMv));
  EXPECT_NEAR(*d.zeta, b / (2 * std::sqrt(k * kMv)), 1e-6);
  EXPECT_NEAR(*d.m_eff_kg, kMv, 1e-6 * kMv);  // k_o explains all the stiffness
  EXPECT_NEAR(*d.b_o_N_s_per_m, kBo, 1e-5 * kBo);
  // E' = k_o / (2a) at every line, E'' = w b_o / (2a): their band means; a from the Sneddon sphere
  const double a = kKo / (2 * *d.E_storage_Pa);
  EXPECT_NEAR(0.5 * a * std::log((kTip + a) / (kTip - a)), kDelta0, 1e-9);
  double mean_w = 0, var = 0;
  for (const an::FrfLine& l : run.frf->lines) {
    mean_w += 2 * std::numbers::pi * l.f_Hz;
    const double s = l.sigma_m_per_N / std::norm(l.G_m_per_N) / (2 * a);
    var += s * s;
  }
  const double n = static_cast<double>(run.frf->lines.size());
  mean_w /= n;
  EXPECT_NEAR(*d.E_loss_Pa, mean_w * kBo / (2 * a), 1e-6 * *d.E_loss_Pa);
  ASSERT_TRUE(d.E_storage_Pa_se && d.E_loss_Pa_se);
  EXPECT_NEAR(*d.E_storage_Pa_se, std::sqrt(var) / n, 1e-9 * *d.E_storage_Pa_se);
  // no standard error of k_o (no fitted model behind it): m_eff and b_o without one, and why
  EXPECT_FALSE(d.m_eff_kg_se);
  EXPECT_NE(d.reason.find("no standard error of k_o"), std::string::npos) << d.reason;
}

TEST(MapDynamic, WithoutTheIndentationOnlyOmegaNAndZetaAndTheReasonForTheRest) {
  const palp::DynamicPoint d = palp::dynamic_point_of(kelvin_voigt_run(), nullptr, {});
  EXPECT_TRUE(d.omega_n_rad_per_s && d.zeta);
  EXPECT_FALSE(d.m_eff_kg || d.b_o_N_s_per_m || d.E_storage_Pa || d.E_loss_Pa);
  EXPECT_NE(d.reason.find("no static k_o at the bias: the indentation was not analysed"),
            std::string::npos)
      << d.reason;
  palp::IdentificationRun none;
  none.analysis_reason = "too few lines";
  EXPECT_EQ(palp::dynamic_point_of(none, nullptr, {}).reason, "too few lines");
  // a fit the decomposition refuses (zeta <= 0) leaves m_eff, b_o and the moduli absent with
  // the refusal as the reason, rather than stopping a map
  palp::IdentificationRun bad = kelvin_voigt_run();
  bad.fit->zeta = -0.01;
  const an::IndentationResult ind = indentation_at_bias();
  const palp::DynamicPoint r = palp::dynamic_point_of(bad, &ind, {});
  EXPECT_FALSE(r.m_eff_kg || r.E_storage_Pa);
  EXPECT_NE(r.reason.find("zeta"), std::string::npos) << r.reason;
}

TEST(MapDynamic, PointKeysRoundTripThroughMapJsonAndABadValueIsNamed) {
  palp::MapPoint p;
  p.dynamic_dir = "points/r1_c2_dynamic";
  an::IndentationParams params;
  params.tip_radius_m = kTip;
  const an::IndentationResult ind = indentation_at_bias();
  p.dynamic = palp::dynamic_point_of(kelvin_voigt_run(), &ind, params);
  nlohmann::json j;
  palp::write_dynamic_point(j, p);
  EXPECT_TRUE(j["m_eff_kg_se"].is_null());
  EXPECT_EQ(j["m_eff_kg_se_reason"], p.dynamic.reason);
  palp::MapPoint back;
  palp::read_dynamic_point(j, "map.json: points[0]", back);
  EXPECT_EQ(back.dynamic_dir, p.dynamic_dir);
  EXPECT_EQ(back.dynamic.reason, p.dynamic.reason);
  for (const palp::DynamicQuantity& q : palp::dynamic_quantities()) {
    EXPECT_EQ(back.dynamic.*q.value, p.dynamic.*q.value) << q.key;
    EXPECT_EQ(back.dynamic.*q.se, p.dynamic.*q.se) << q.key;
  }
  // a quasi-static point writes no dynamic key
  nlohmann::json plain;
  palp::write_dynamic_point(plain, palp::MapPoint{});
  EXPECT_TRUE(plain.is_null());
  j["zeta"] = "0.2";
  try {
    palp::read_dynamic_point(j, "map.json: points[0]", back);
    FAIL() << "a string zeta was read";
  } catch (const palp::ConfigError& e) {
    EXPECT_STREQ(e.what(), "map.json: points[0]: \"zeta\" must be a number or null");
  }
}

}  // namespace
