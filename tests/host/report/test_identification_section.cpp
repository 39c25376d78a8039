// SPDX-License-Identifier: Apache-2.0
// The identification section's figures (host/src/report/identification_section.cpp) from a
// known second-order system G = 1 / (m s² + b s + k), m = 0.16 kg, k = 400 N/m, ζ = 0.2
// (ω_n = 50 rad/s, f_n = 7.958 Hz): the measured points and the model curve are that G, the
// phase runs from 0 to −180°, the moduli are the contact's known k′ and k″ over 2a.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "palp/error.hpp"
#include "report/sections.hpp"
#include "report_plots_synth.hpp"

namespace {

using nlohmann::json;
using palp_test::report::data_values;
using palp_test::report::interpolate;
namespace rt = palp_test::report;

constexpr double kPi = 3.14159265358979323846;

std::complex<double> G(double f) {
  const double w = 2 * kPi * f;
  return 1.0 / std::complex<double>(rt::kK_N_per_m - rt::kM_kg * w * w, rt::known_b() * w);
}
double dB(double v) { return 20 * std::log10(v); }

class IdentificationSection : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto dir = rt::fresh_dir("identification");
    section_ = new palp::report::Section(palp::report::identification_section(
        palp::load_result(rt::write_known_identification(dir / "solid-p3-sweep"))));
  }
  static void TearDownTestSuite() { delete section_; }
  static const json& spec(const std::string& id) {
    for (const auto& f : section_->figures)
      if (f.id == id) return f.spec;
    throw std::out_of_range("no figure " + id);
  }
  static palp::report::Section* section_;
};
palp::report::Section* IdentificationSection::section_ = nullptr;

TEST_F(IdentificationSection, MagnitudePointsAndModelAreTheKnownResponseInDecibels) {
  const json& s = spec("identification-bode-magnitude");
  EXPECT_EQ(s["axes"][0]["title"], "f (Hz)");
  EXPECT_EQ(s["axes"][1]["title"], "|G| (dB re 1 m/N)");
  EXPECT_EQ(s["scales"][0]["type"], "log");
  const json& pts = data_values(s, "measured");
  ASSERT_EQ(pts.size(), 80u);  // 0.5 to 40 Hz by 0.5 Hz
  const double sigma = 0.02 * std::abs(G(8.0));
  for (const auto& p : pts) {
    const double f = p["f_Hz"];
    EXPECT_NEAR(p["mag_dB"].get<double>(), dB(std::abs(G(f))), 1e-9) << f;
    EXPECT_NEAR(p["hi_dB"].get<double>(), dB(std::abs(G(f)) + sigma), 1e-9) << f;
  }
  // the fitted model passes through the truth everywhere, the resonance peak included
  const json& model = data_values(s, "model");
  for (double f : {0.5, 5.0, 7.958, 10.0, 40.0})
    EXPECT_NEAR(interpolate(model, "f_Hz", "mag_dB", f), dB(std::abs(G(f))), 0.02) << f;
  // the peak: 1 / (2 ζ k sqrt(1 - ζ²)) = -43.9 dB; the static gain 1/k = -52.0 dB
  EXPECT_NEAR(interpolate(model, "f_Hz", "mag_dB", 0.5), dB(1 / rt::kK_N_per_m), 0.05);
}

TEST_F(IdentificationSection, PhaseRunsFromZeroToMinus180WithTheModel) {
  const json& s = spec("identification-bode-phase");
  EXPECT_EQ(s["axes"][1]["title"], "phase (deg)");
  EXPECT_EQ(s["scales"][1]["domain"], json::array({-180.0, 0.0}));
  const json& pts = data_values(s, "measured");
  for (const auto& p : pts) {
    const double f = p["f_Hz"];
    EXPECT_NEAR(p["phase_deg"].get<double>(), std::arg(G(f)) * 180 / kPi, 1e-9) << f;
  }
  const json& model = data_values(s, "model");
  EXPECT_NEAR(interpolate(model, "f_Hz", "phase_deg", rt::known_omega_n() / (2 * kPi)), -90.0, 0.2);
  EXPECT_LT(pts.back()["phase_deg"].get<double>(), -170.0);  // 40 Hz: −175.2°
}

TEST_F(IdentificationSection, ModuliAreTheContactsKnownStiffnessOverTheContactDiameter) {
  const json& s = spec("identification-moduli");
  EXPECT_EQ(s["axes"][1]["title"], "E′, E″ (Pa)");
  // k′ = k − k_v − (m − m_v) ω², k″ = (b − b_v) ω with the paper's m_v, b_v, k_v; E = k / (2a)
  const double a = 1.475e-3;  // Sneddon's contact radius at δ0 = 1 mm, R = 2.5 mm
  for (const auto& p : data_values(s, "moduli")) {
    const double w = 2 * kPi * p["f_Hz"].get<double>();
    const double k1 = rt::kK_N_per_m - 43.9 - (rt::kM_kg - 0.1609) * w * w;
    const double k2 = (rt::known_b() - 1.379) * w;
    EXPECT_NEAR(p["E_storage_Pa"].get<double>(), k1 / (2 * a), 0.002 * k1 / (2 * a));
    EXPECT_NEAR(p["E_loss_Pa"].get<double>(), k2 / (2 * a), 0.002 * k2 / (2 * a));
    EXPECT_NEAR(p["tan_delta"].get<double>(), k2 / k1, 1e-6);
  }
}

TEST_F(IdentificationSection, ModuliOfLinesWhoseNoiseSwampsTheContactStiffnessAreMarkedAndLeftOffTheAxes) {
  const json& s = spec("identification-moduli");
  const double sigma = 0.02 * std::abs(G(8.0));
  double trusted_max = 0;
  for (const auto& p : data_values(s, "moduli")) {
    const double f = p["f_Hz"], w = 2 * kPi * f;
    // 1/G's error σ/|G|² against the contact stiffness |k′ + j k″| (k′, k″ as above)
    const double k = std::hypot(rt::kK_N_per_m - 43.9 - (rt::kM_kg - 0.1609) * w * w, (rt::known_b() - 1.379) * w);
    const bool noisy = sigma / std::norm(G(f)) / k > 0.2;
    EXPECT_EQ(p["noisy"].get<double>(), noisy ? 1.0 : 0.0) << f;
    if (!noisy) trusted_max = std::max(trusted_max, p["E_storage_Pa"].get<double>());
  }
  EXPECT_EQ(data_values(s, "moduli").front()["noisy"], 0.0);  // 0.5 Hz: σ/|G|² ~ 5 % of |k*|
  EXPECT_EQ(data_values(s, "moduli").back()["noisy"], 1.0);   // 40 Hz: ~20 times |k*|
  // the E axis spans the trusted lines (a 2 % pad)
  EXPECT_NEAR(s["scales"][1]["domain"][1].get<double>(), trusted_max, 0.03 * trusted_max);
}

TEST_F(IdentificationSection, TheTableGivesOmegaNAndZetaWithTheirErrorsAndTheInstrument) {
  const auto& rows = section_->tables.at(0).rows;
  const auto find = [&](const std::string& q) {
    const auto it = std::find_if(rows.begin(), rows.end(), [&](const auto& r) { return r[0] == q; });
    if (it == rows.end()) throw std::out_of_range(q);
    return *it;
  };
  EXPECT_NEAR(std::stod(find("ω_n")[2]), 50.0, 1e-3);
  EXPECT_FALSE(find("ω_n")[3].empty());
  EXPECT_NEAR(std::stod(find("ζ")[2]), 0.2, 1e-4);
  EXPECT_NEAR(std::stod(find("f_n")[2]), 7.9577, 1e-3);
  EXPECT_EQ(find("instrument m_v (used)")[2], "0.1609");
  EXPECT_EQ(find("instrument b_v (used)")[2], "1.379");
}

TEST(IdentificationSectionErrors, AnIndentationResultIsRefusedNamingIt) {
  const auto dir = rt::fresh_dir("identification-refused");
  const auto loaded = palp::load_result(rt::write_known_indentation(dir / "r"));
  try {
    palp::report::identification_section(loaded);
    FAIL() << "no RecordingError";
  } catch (const palp::RecordingError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("not an identification"));
  }
}

TEST(IdentificationSectionErrors, AMissingFrequencyResponseIsNamed) {
  const auto dir = rt::fresh_dir("identification-no-frf");
  const auto path = rt::write_known_identification(dir / "r");
  const auto loaded = palp::load_result(path);
  std::filesystem::remove(path / "frf.csv");
  try {
    palp::report::identification_section(loaded);
    FAIL() << "no RecordingError";
  } catch (const palp::RecordingError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("frf.csv"));
  }
}

}  // namespace

namespace {

TEST(IdentificationSectionWithoutFit, DrawsTheMeasuredPointsWithoutAModel) {
  const auto dir = palp_test::report::fresh_dir("identification-no-fit");
  const auto path = palp_test::report::write_known_identification(dir / "r");
  auto loaded = palp::load_result(path);
  loaded.summary["analysis"] = nullptr;
  loaded.summary["analysis_reason"] = "too few lines";
  const auto s = palp::report::identification_section(loaded);
  ASSERT_EQ(s.figures.size(), 2u);  // no moduli without an analysis
  EXPECT_THAT(s.text, testing::HasSubstr("No second-order fit in result.json: too few lines"));
  for (const auto& f : s.figures) {
    EXPECT_EQ(palp_test::report::data_values(f.spec, "measured").size(), 80u);
    EXPECT_TRUE(palp_test::report::data_values(f.spec, "model").empty());
  }
  EXPECT_EQ(s.figures[1].spec["scales"][1]["domain"], nlohmann::json::array({-180.0, 0.0}));
}

}  // namespace
