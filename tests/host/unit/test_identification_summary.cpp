// SPDX-License-Identifier: Apache-2.0
// The identification summaries (palp/identification_result.hpp): each written and read through one
// field table, in lab units; a number that is not finite written null with `<key>_reason`; a
// missing key named in result.json's way.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "palp/error.hpp"
#include "palp/identification_result.hpp"

namespace {

namespace an = palp::analysis;
using nlohmann::json;

/// The ConfigError text `f` throws ("" when it throws none).
template <class F>
std::string summary_error(F f) {
  try {
    f();
  } catch (const palp::ConfigError& e) {
    return e.what();
  }
  return "";
}

an::FreeAirResult distinct_free_air() {
  an::FreeAirResult r;
  r.omega_n_rad_per_s = 1234.5;
  r.zeta = 0.125;
  r.k_v_N_per_m = 250.0;  // 0.25 N/mm
  r.m_v_kg = 0.161;
  r.m_v_kg_se = 0.002;
  r.b_v_N_s_per_m = 1.38;
  r.b_v_N_s_per_m_se = 0.03;
  return r;
}

TEST(IdentificationSummaryJson, FreeAirWritesLabUnitsAndReadsBackEveryField) {
  const auto r = distinct_free_air();
  const json j = palp::free_air_json(r);
  EXPECT_EQ(j.dump(),
            R"({"b_v_N_s_per_m":1.38,"b_v_N_s_per_m_se":0.03,"kv_N_per_mm":0.25,"m_v_kg":0.161,)"
            R"("m_v_kg_se":0.002,"omega_n_rad_per_s":1234.5,"zeta":0.125})");
  const auto back = palp::free_air_from_json(json{{"free_air", j}});
  EXPECT_EQ(back.omega_n_rad_per_s, r.omega_n_rad_per_s);
  EXPECT_EQ(back.zeta, r.zeta);
  EXPECT_EQ(back.k_v_N_per_m, r.k_v_N_per_m);
  EXPECT_EQ(back.m_v_kg, r.m_v_kg);
  EXPECT_EQ(back.m_v_kg_se, r.m_v_kg_se);
  EXPECT_EQ(back.b_v_N_s_per_m, r.b_v_N_s_per_m);
  EXPECT_EQ(back.b_v_N_s_per_m_se, r.b_v_N_s_per_m_se);
}

TEST(IdentificationSummaryJson, FreeAirNotFiniteIsNullWithReasonAndReadsBackAsNaN) {
  auto r = distinct_free_air();
  r.m_v_kg_se = NAN;
  const json j = palp::free_air_json(r);
  EXPECT_TRUE(j["m_v_kg_se"].is_null());
  EXPECT_EQ(j["m_v_kg_se_reason"], "not finite");
  EXPECT_FALSE(j.contains("m_v_kg_reason"));
  const auto back = palp::free_air_from_json(json{{"free_air", j}});
  EXPECT_TRUE(std::isnan(back.m_v_kg_se));
  EXPECT_EQ(back.m_v_kg, r.m_v_kg);
}

TEST(IdentificationSummaryJson, FreeAirReaderNamesAMissingKeyANullInstrumentValueAndNoObject) {
  json j = {{"free_air", palp::free_air_json(distinct_free_air())}};
  j["free_air"].erase("m_v_kg");
  EXPECT_EQ(summary_error([&] { palp::free_air_from_json(j); }), "missing key \"free_air.m_v_kg\"");
  j["free_air"]["m_v_kg"] = nullptr;
  j["free_air"]["m_v_kg_reason"] = "the fit did not converge";
  EXPECT_EQ(summary_error([&] { palp::free_air_from_json(j); }),
            "\"free_air.m_v_kg\" is null (the fit did not converge)");
  j["free_air"]["m_v_kg"] = "0.1";
  EXPECT_EQ(summary_error([&] { palp::free_air_from_json(j); }), "\"free_air.m_v_kg\" is not a number");
  EXPECT_EQ(summary_error([] { palp::free_air_from_json(json::object()); }), "missing key \"free_air\"");
}

an::Decomposition distinct_decomposition() {
  an::Decomposition d;
  d.k_o_N_per_m = 500.0;
  d.k_eff_N_per_m = 750.0;
  d.m_eff_kg = 0.2;
  d.m_eff_kg_se = 0.01;
  d.b_total_N_s_per_m = 3.5;
  d.b_total_N_s_per_m_se = 0.2;
  d.b_o_N_s_per_m = 2.1;
  d.b_o_N_s_per_m_se = 0.15;
  d.m_o_kg = 0.04;
  return d;
}

TEST(IdentificationSummaryJson, DecompositionWritesLabUnitsAndNoteAndReadsBackEveryField) {
  const auto d = distinct_decomposition();
  const json j = palp::decomposition_json(d);
  EXPECT_EQ(j["k_o_N_per_mm"], 0.5);
  EXPECT_EQ(j["k_eff_N_per_mm"], 0.75);
  EXPECT_THAT(j["m_eff_note"].get<std::string>(), testing::HasSubstr("m_eff = k_eff / omega_n^2"));
  EXPECT_EQ(j.size(), 10u);
  const auto back = palp::decomposition_from_json(j);
  EXPECT_EQ(back.k_o_N_per_m, d.k_o_N_per_m);
  EXPECT_EQ(back.k_eff_N_per_m, d.k_eff_N_per_m);
  EXPECT_EQ(back.m_eff_kg, d.m_eff_kg);
  EXPECT_EQ(back.m_eff_kg_se, d.m_eff_kg_se);
  EXPECT_EQ(back.b_total_N_s_per_m, d.b_total_N_s_per_m);
  EXPECT_EQ(back.b_total_N_s_per_m_se, d.b_total_N_s_per_m_se);
  EXPECT_EQ(back.b_o_N_s_per_m, d.b_o_N_s_per_m);
  EXPECT_EQ(back.b_o_N_s_per_m_se, d.b_o_N_s_per_m_se);
  EXPECT_EQ(back.m_o_kg, d.m_o_kg);
}

TEST(IdentificationSummaryJson, DecompositionReaderNamesAMissingKey) {
  json j = palp::decomposition_json(distinct_decomposition());
  j.erase("b_o_N_s_per_m_se");
  EXPECT_EQ(summary_error([&] { palp::decomposition_from_json(j); }), "missing key \"b_o_N_s_per_m_se\"");
}

an::Viscoelastic distinct_viscoelastic() {
  an::Viscoelastic v;
  v.delta0_m = 1.5e-3;
  v.tip_radius_m = 2.5e-3;
  v.contact_radius_m = 1.75e-3;
  v.flagged = true;
  v.flag_reason = "delta0 > R/2";
  v.lines = {{10.0, 400.0, 50.0, 1.1e5, 1.4e4, 0.125}, {20.0, 410.0, 60.0, 1.2e5, 1.7e4, NAN}};
  return v;
}

TEST(IdentificationSummaryJson, ViscoelasticWritesLinesAndReadsBackEveryField) {
  const auto v = distinct_viscoelastic();
  const json j = palp::viscoelastic_json(v);
  EXPECT_EQ(j["delta0_mm"], 1.5);
  EXPECT_EQ(j["flag_reason"], "delta0 > R/2");
  EXPECT_EQ(j["lines"][0].dump(),
            R"({"E_loss_Pa":14000.0,"E_storage_Pa":110000.0,"f_Hz":10.0,"k_loss_N_per_mm":0.05,)"
            R"("k_storage_N_per_mm":0.4,"tan_delta":0.125})");
  EXPECT_TRUE(j["lines"][1]["tan_delta"].is_null());
  EXPECT_EQ(j["lines"][1]["tan_delta_reason"], "not finite");

  const auto back = palp::viscoelastic_from_json(json{{"viscoelastic", j}});
  EXPECT_DOUBLE_EQ(back.delta0_m, v.delta0_m);
  EXPECT_DOUBLE_EQ(back.tip_radius_m, v.tip_radius_m);
  EXPECT_DOUBLE_EQ(back.contact_radius_m, v.contact_radius_m);
  EXPECT_EQ(back.flagged, v.flagged);
  EXPECT_EQ(back.flag_reason, v.flag_reason);
  ASSERT_EQ(back.lines.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(back.lines[k].f_Hz, v.lines[k].f_Hz);
    EXPECT_DOUBLE_EQ(back.lines[k].k_storage_N_per_m, v.lines[k].k_storage_N_per_m);
    EXPECT_DOUBLE_EQ(back.lines[k].k_loss_N_per_m, v.lines[k].k_loss_N_per_m);
    EXPECT_EQ(back.lines[k].E_storage_Pa, v.lines[k].E_storage_Pa);
    EXPECT_EQ(back.lines[k].E_loss_Pa, v.lines[k].E_loss_Pa);
  }
  EXPECT_EQ(back.lines[0].tan_delta, 0.125);
  EXPECT_TRUE(std::isnan(back.lines[1].tan_delta));
}

TEST(IdentificationSummaryJson, ViscoelasticReaderNamesAMissingKeyInALine) {
  json j = {{"viscoelastic", palp::viscoelastic_json(distinct_viscoelastic())}};
  j["viscoelastic"]["lines"][1].erase("k_loss_N_per_mm");
  EXPECT_EQ(summary_error([&] { palp::viscoelastic_from_json(j); }),
            "missing key \"viscoelastic.lines[1].k_loss_N_per_mm\"");
  j["viscoelastic"].erase("lines");
  EXPECT_EQ(summary_error([&] { palp::viscoelastic_from_json(j); }), "missing key \"viscoelastic.lines\"");
}

TEST(IdentificationSummaryJson, SweepSummaryWritesTheFitInLabUnitsAndNullsWithTheirReasons) {
  an::Frf frf;
  frf.method = "stepped_sine";
  frf.lines = {{}, {}};
  frf.lines[0].f_Hz = 5.0;
  frf.lines[1].f_Hz = 40.0;
  frf.line_spacing_Hz = 0.05;
  frf.device_time_s = 12.5;
  frf.notes = {"a note"};
  an::SecondOrderFit fit;
  fit.omega_n_rad_per_s = 100.0;
  fit.omega_n_rad_per_s_se = 1.0;
  fit.zeta = 0.2;
  fit.zeta_se = NAN;
  fit.m_kg = 0.16;
  fit.m_kg_se = 0.004;
  fit.b_N_s_per_m = 6.4;
  fit.b_N_s_per_m_se = 0.1;
  fit.k_N_per_m = 1600.0;
  fit.k_N_per_m_se = 20.0;
  fit.adequate = false;
  fit.converged = true;
  const json j = palp::sweep_summary_json(frf, fit);
  EXPECT_EQ(j["method"], "stepped_sine");
  EXPECT_EQ(j["lines"], 2);
  EXPECT_EQ(j["f_lo_Hz"], 5.0);
  EXPECT_EQ(j["f_hi_Hz"], 40.0);
  EXPECT_EQ(j["line_spacing_Hz"], 0.05);
  EXPECT_EQ(j["device_time_s"], 12.5);
  EXPECT_EQ(j["notes"], json::array({"a note"}));
  EXPECT_EQ(j["f_n_Hz"], 100.0 / (2 * M_PI));
  EXPECT_EQ(j["k_N_per_mm"], 1.6);
  EXPECT_EQ(j["k_N_per_mm_se"], 0.02);
  EXPECT_TRUE(j["zeta_se"].is_null());
  EXPECT_EQ(j["zeta_se_reason"], "not finite");
  EXPECT_TRUE(j["normalized_cost"].is_null());
  EXPECT_EQ(j["normalized_cost_reason"], "the lines carry no noise estimate (a table without sigma)");
  EXPECT_EQ(j["adequate"], false);
  EXPECT_EQ(j["fit_converged"], true);
  EXPECT_TRUE(j["distortion"].is_null());
  EXPECT_EQ(j["distortion_reason"], "only a multisine's empty lines measure distortion");
  EXPECT_EQ(j.size(), 25u);
}

}  // namespace
