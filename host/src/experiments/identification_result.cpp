// SPDX-License-Identifier: Apache-2.0
// Identification results in lab units (identification_result.hpp).
#include "palp/identification_result.hpp"

#include <charconv>
#include <cmath>

#include "format/field_table.hpp"
#include "palp/error.hpp"
#include "palp/result.hpp"
#include "result_dir.hpp"
#include "run_json.hpp"

namespace palp {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

namespace an = analysis;
using format::Field;
using format::kMm;
using format::kNPerMm;
using format::Need;
constexpr const char* kSweepStem = "sweep";

// The summaries' numbers, each a number or null with `<key>_reason` (Need::or_null).
const Field<an::SecondOrderFit> kFitSummaryFields[] = {
    {"omega_n_rad_per_s", &an::SecondOrderFit::omega_n_rad_per_s, 1.0, Need::or_null},
    {"omega_n_rad_per_s_se", &an::SecondOrderFit::omega_n_rad_per_s_se, 1.0, Need::or_null},
    {"zeta", &an::SecondOrderFit::zeta, 1.0, Need::or_null},
    {"zeta_se", &an::SecondOrderFit::zeta_se, 1.0, Need::or_null},
    {"m_kg", &an::SecondOrderFit::m_kg, 1.0, Need::or_null},
    {"m_kg_se", &an::SecondOrderFit::m_kg_se, 1.0, Need::or_null},
    {"b_N_s_per_m", &an::SecondOrderFit::b_N_s_per_m, 1.0, Need::or_null},
    {"b_N_s_per_m_se", &an::SecondOrderFit::b_N_s_per_m_se, 1.0, Need::or_null},
    {"k_N_per_mm", &an::SecondOrderFit::k_N_per_m, kNPerMm, Need::or_null},
    {"k_N_per_mm_se", &an::SecondOrderFit::k_N_per_m_se, kNPerMm, Need::or_null},
    {"normalized_cost", &an::SecondOrderFit::normalized_cost, 1.0, Need::or_null, {},
     "the lines carry no noise estimate (a table without sigma)"},
    {"adequate", &an::SecondOrderFit::adequate},
    {"fit_converged", &an::SecondOrderFit::converged},
};

const Field<an::Frf> kFrfSummaryFields[] = {
    {"method", &an::Frf::method},
    {"line_spacing_Hz", &an::Frf::line_spacing_Hz},
    {"device_time_s", &an::Frf::device_time_s},
};

const Field<an::FrfDistortion> kDistortionSummaryFields[] = {
    {"even_ratio", &an::FrfDistortion::even_ratio},
    {"odd_ratio", &an::FrfDistortion::odd_ratio},
    {"excited_rms_mm", &an::FrfDistortion::excited_rms_m, kMm},
    {"even_rms_mm", &an::FrfDistortion::even_rms_m, kMm},
    {"odd_rms_mm", &an::FrfDistortion::odd_rms_m, kMm},
    {"noise_rms_mm", &an::FrfDistortion::noise_rms_m, kMm},
    {"too_large", &an::FrfDistortion::too_large},
    {"warning", &an::FrfDistortion::warning},
};

const Field<an::FreeAirResult> kFreeAirSummaryFields[] = {
    {"omega_n_rad_per_s", &an::FreeAirResult::omega_n_rad_per_s, 1.0, Need::or_null},
    {"zeta", &an::FreeAirResult::zeta, 1.0, Need::or_null},
    {"kv_N_per_mm", &an::FreeAirResult::k_v_N_per_m, kNPerMm, Need::or_null},
    {"m_v_kg", &an::FreeAirResult::m_v_kg, 1.0, Need::or_null},
    {"m_v_kg_se", &an::FreeAirResult::m_v_kg_se, 1.0, Need::or_null},
    {"b_v_N_s_per_m", &an::FreeAirResult::b_v_N_s_per_m, 1.0, Need::or_null},
    {"b_v_N_s_per_m_se", &an::FreeAirResult::b_v_N_s_per_m_se, 1.0, Need::or_null},
};

const Field<an::Decomposition> kDecompositionSummaryFields[] = {
    {"k_o_N_per_mm", &an::Decomposition::k_o_N_per_m, kNPerMm, Need::or_null},
    {"k_eff_N_per_mm", &an::Decomposition::k_eff_N_per_m, kNPerMm, Need::or_null},
    {"m_eff_kg", &an::Decomposition::m_eff_kg, 1.0, Need::or_null},
    {"m_eff_kg_se", &an::Decomposition::m_eff_kg_se, 1.0, Need::or_null},
    {"b_total_N_s_per_m", &an::Decomposition::b_total_N_s_per_m, 1.0, Need::or_null},
    {"b_total_N_s_per_m_se", &an::Decomposition::b_total_N_s_per_m_se, 1.0, Need::or_null},
    {"b_o_N_s_per_m", &an::Decomposition::b_o_N_s_per_m, 1.0, Need::or_null},
    {"b_o_N_s_per_m_se", &an::Decomposition::b_o_N_s_per_m_se, 1.0, Need::or_null},
    {"m_o_kg", &an::Decomposition::m_o_kg, 1.0, Need::or_null},
};
constexpr const char* kMEffNote =
    "m_eff = k_eff / omega_n^2 with the static k_eff, as the paper computes it: it folds any "
    "dynamic stiffening into an apparent mass; m_kg is the fit's own mass";

const Field<an::Viscoelastic> kViscoelasticSummaryFields[] = {
    {"delta0_mm", &an::Viscoelastic::delta0_m, kMm},
    {"tip_radius_mm", &an::Viscoelastic::tip_radius_m, kMm},
    {"contact_radius_mm", &an::Viscoelastic::contact_radius_m, kMm},
    {"flagged", &an::Viscoelastic::flagged},
};

const Field<an::ViscoelasticLine> kViscoelasticLineSummaryFields[] = {
    {"f_Hz", &an::ViscoelasticLine::f_Hz},
    {"k_storage_N_per_mm", &an::ViscoelasticLine::k_storage_N_per_m, kNPerMm, Need::or_null},
    {"k_loss_N_per_mm", &an::ViscoelasticLine::k_loss_N_per_m, kNPerMm, Need::or_null},
    {"E_storage_Pa", &an::ViscoelasticLine::E_storage_Pa, 1.0, Need::or_null},
    {"E_loss_Pa", &an::ViscoelasticLine::E_loss_Pa, 1.0, Need::or_null},
    {"tan_delta", &an::ViscoelasticLine::tan_delta, 1.0, Need::or_null},
};

/// `j`'s object `key` (ConfigError naming it when absent or not an object).
const json& summary_object(const json& j, const char* key, const std::string& where) {
  const auto it = j.find(key);
  if (it == j.end()) throw ConfigError("missing key \"" + where + key + "\"");
  if (!it->is_object()) throw ConfigError("\"" + where + key + "\" is not an object");
  return *it;
}

std::string shortest(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace

json sweep_summary_json(const an::Frf& frf, const an::SecondOrderFit& fit) {
  json j;
  format::write_fields(j, frf, kFrfSummaryFields);
  j["lines"] = frf.lines.size();
  j["f_lo_Hz"] = frf.lines.empty() ? 0.0 : frf.lines.front().f_Hz;
  j["f_hi_Hz"] = frf.lines.empty() ? 0.0 : frf.lines.back().f_Hz;
  j["notes"] = frf.notes;
  format::write_fields(j, fit, kFitSummaryFields);
  format::put_or_null(j, "f_n_Hz", fit.omega_n_rad_per_s / (2 * M_PI));
  if (frf.distortion) {
    format::write_fields(j["distortion"], *frf.distortion, kDistortionSummaryFields);
  } else {
    j["distortion"] = nullptr;
    j["distortion_reason"] = frf.method == "multisine"
                                 ? "no empty lines in the band"
                                 : "only a multisine's empty lines measure distortion";
  }
  return j;
}

json free_air_json(const an::FreeAirResult& r) {
  json j;
  format::write_fields(j, r, kFreeAirSummaryFields);
  return j;
}

an::FreeAirResult free_air_from_json(const json& analysis) {
  an::FreeAirResult r;
  const format::JsonSource f(summary_object(analysis, "free_air", ""), "free_air.", format::Naming::dotted_path);
  format::read_fields(f, r, kFreeAirSummaryFields);
  for (const auto& [key, v] : {std::pair{"m_v_kg", r.m_v_kg}, {"b_v_N_s_per_m", r.b_v_N_s_per_m}})
    if (!std::isfinite(v)) f.fail(key, "is null (" + f.reason(key) + ")");
  return r;
}

json decomposition_json(const an::Decomposition& d) {
  json j;
  format::write_fields(j, d, kDecompositionSummaryFields);
  j["m_eff_note"] = kMEffNote;
  return j;
}

an::Decomposition decomposition_from_json(const json& analysis) {
  an::Decomposition d;
  format::read_fields(format::JsonSource(analysis, "", format::Naming::dotted_path), d, kDecompositionSummaryFields);
  return d;
}

json viscoelastic_json(const an::Viscoelastic& v) {
  json j;
  format::write_fields(j, v, kViscoelasticSummaryFields);
  if (v.flagged) j["flag_reason"] = v.flag_reason;
  json lines = json::array();
  for (const auto& l : v.lines) {
    json row;
    format::write_fields(row, l, kViscoelasticLineSummaryFields);
    lines.push_back(std::move(row));
  }
  j["lines"] = std::move(lines);
  return j;
}

an::Viscoelastic viscoelastic_from_json(const json& analysis) {
  an::Viscoelastic v;
  const json& j = summary_object(analysis, "viscoelastic", "");
  format::read_fields(format::JsonSource(j, "viscoelastic.", format::Naming::dotted_path), v, kViscoelasticSummaryFields);
  if (v.flagged) v.flag_reason = format::JsonSource(j, "viscoelastic.", format::Naming::dotted_path).text("flag_reason");
  const auto it = j.find("lines");
  if (it == j.end()) throw ConfigError("missing key \"viscoelastic.lines\"");
  if (!it->is_array()) throw ConfigError("\"viscoelastic.lines\" is not an array");
  for (std::size_t k = 0; k < it->size(); ++k) {
    const json& row = (*it)[k];
    const std::string where = "viscoelastic.lines[" + std::to_string(k) + "].";
    if (!row.is_object()) throw ConfigError("\"" + where.substr(0, where.size() - 1) + "\" is not an object");
    an::ViscoelasticLine l;
    format::read_fields(format::JsonSource(row, where, format::Naming::dotted_path), l, kViscoelasticLineSummaryFields);
    v.lines.push_back(l);
  }
  return v;
}

std::string format_frf_table(const analysis::Frf& frf) {
  std::string out = "# palp frequency response G = Z/F, x = Re{X exp(j w t)} (passive: im <= 0); method " +
                    frf.method + "\nf_Hz,re_m_per_N,im_m_per_N,sigma_m_per_N\n";
  for (const auto& l : frf.lines) {
    out += shortest(l.f_Hz) + ',' + shortest(l.G_m_per_N.real()) + ',' + shortest(l.G_m_per_N.imag()) +
           ',' + shortest(l.sigma_m_per_N) + '\n';
  }
  return out;
}

fs::path write_identification_result(const fs::path& dir_in, const IdentificationRun& run,
                                     const json& analysis, Overwrite overwrite) {
  if (run.recording.size() == 0)
    throw ConfigError("write_identification_result: the run has no samples; nothing to write");
  const fs::path dir = prepare_result_directory(dir_in, overwrite, "write_identification_result");

  nlohmann::ordered_json summary = result_head("identification");
  const auto& sc = run.recording.sidecar;
  summary["device"] = sc ? sc->device : device_json(run.device);
  summary["firmware_version"] = run.device.firmware_version;
  summary["parameters"] = sc && sc->extra.contains("identification") ? sc->extra["identification"] : json(nullptr);
  summary["recordings"] = json::array({std::string(kSweepStem) + ".csv"});
  summary["run"] = identification_run_json(run);
  summary["analysis"] = analysis;
  if (analysis.is_null())
    summary["analysis_reason"] = run.analysis_reason.empty() ? "not analysed" : run.analysis_reason;

  write_result_directory(dir, overwrite, [&](const fs::path& tmp) {
    write_recording(tmp / kSweepStem, run.recording);
    if (run.frf) write_text_file(tmp / "frf.csv", format_frf_table(*run.frf));
    write_text_file(tmp / std::string(kResultFile), summary.dump(2) + "\n");
  });
  return dir;
}

}  // namespace palp
