// Identification results in lab units (identification_result.hpp).
#include "palp/identification_result.hpp"

#include <charconv>
#include <cmath>

#include "palp/error.hpp"
#include "palp/result.hpp"
#include "result_dir.hpp"

namespace palp {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kPerMm = 1e-3;   // N/m -> N/mm
constexpr double kMm = 1e3;       // m -> mm
constexpr const char* kSweepStem = "sweep";

/// A finite number, or null with `<key>_reason`.
void put(json& j, const std::string& key, double v, const char* why_not = "not finite") {
  if (std::isfinite(v)) {
    j[key] = v;
  } else {
    j[key] = nullptr;
    j[key + "_reason"] = why_not;
  }
}

void put_se(json& j, const std::string& key, double v, double se) {
  put(j, key, v);
  put(j, key + "_se", se);
}

std::string shortest(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace

json sweep_summary_json(const analysis::Frf& frf, const analysis::SecondOrderFit& fit) {
  json j;
  j["method"] = frf.method;
  j["lines"] = frf.lines.size();
  j["line_spacing_Hz"] = frf.line_spacing_Hz;
  j["f_lo_Hz"] = frf.lines.empty() ? 0.0 : frf.lines.front().f_Hz;
  j["f_hi_Hz"] = frf.lines.empty() ? 0.0 : frf.lines.back().f_Hz;
  j["device_time_s"] = frf.device_time_s;
  j["notes"] = frf.notes;
  put_se(j, "omega_n_rad_per_s", fit.omega_n_rad_per_s, fit.omega_n_rad_per_s_se);
  put(j, "f_n_Hz", fit.omega_n_rad_per_s / (2 * M_PI));
  put_se(j, "zeta", fit.zeta, fit.zeta_se);
  put_se(j, "m_kg", fit.m_kg, fit.m_kg_se);
  put_se(j, "b_N_s_per_m", fit.b_N_s_per_m, fit.b_N_s_per_m_se);
  put_se(j, "k_N_per_mm", fit.k_N_per_m * kPerMm, fit.k_N_per_m_se * kPerMm);
  if (fit.normalized_cost) {
    j["normalized_cost"] = *fit.normalized_cost;
  } else {
    j["normalized_cost"] = nullptr;
    j["normalized_cost_reason"] = "the lines carry no noise estimate (a table without sigma)";
  }
  j["adequate"] = fit.adequate;
  j["fit_converged"] = fit.converged;
  if (frf.distortion) {
    const auto& d = *frf.distortion;
    j["distortion"] = {{"even_ratio", d.even_ratio},         {"odd_ratio", d.odd_ratio},
                       {"excited_rms_mm", d.excited_rms_m * kMm}, {"even_rms_mm", d.even_rms_m * kMm},
                       {"odd_rms_mm", d.odd_rms_m * kMm},     {"noise_rms_mm", d.noise_rms_m * kMm},
                       {"too_large", d.too_large},           {"warning", d.warning}};
  } else {
    j["distortion"] = nullptr;
    j["distortion_reason"] = frf.method == "multisine"
                                 ? "no empty lines in the band"
                                 : "only a multisine's empty lines measure distortion";
  }
  return j;
}

json free_air_json(const analysis::FreeAirResult& r) {
  json j;
  put(j, "omega_n_rad_per_s", r.omega_n_rad_per_s);
  put(j, "zeta", r.zeta);
  put(j, "kv_N_per_mm", r.k_v_N_per_m * kPerMm);
  put_se(j, "m_v_kg", r.m_v_kg, r.m_v_kg_se);
  put_se(j, "b_v_N_s_per_m", r.b_v_N_s_per_m, r.b_v_N_s_per_m_se);
  return j;
}

json decomposition_json(const analysis::Decomposition& d) {
  json j;
  put(j, "k_o_N_per_mm", d.k_o_N_per_m * kPerMm);
  put(j, "k_eff_N_per_mm", d.k_eff_N_per_m * kPerMm);
  put_se(j, "m_eff_kg", d.m_eff_kg, d.m_eff_kg_se);
  put_se(j, "b_total_N_s_per_m", d.b_total_N_s_per_m, d.b_total_N_s_per_m_se);
  put_se(j, "b_o_N_s_per_m", d.b_o_N_s_per_m, d.b_o_N_s_per_m_se);
  put(j, "m_o_kg", d.m_o_kg);
  j["m_eff_note"] =
      "m_eff = k_eff / omega_n^2 with the static k_eff, as the paper computes it: it folds any "
      "dynamic stiffening into an apparent mass; m_kg is the fit's own mass";
  return j;
}

json viscoelastic_json(const analysis::Viscoelastic& v) {
  json j;
  j["delta0_mm"] = v.delta0_m * kMm;
  j["tip_radius_mm"] = v.tip_radius_m * kMm;
  j["contact_radius_mm"] = v.contact_radius_m * kMm;
  j["flagged"] = v.flagged;
  if (v.flagged) j["flag_reason"] = v.flag_reason;
  json lines = json::array();
  for (const auto& l : v.lines) {
    json row = {{"f_Hz", l.f_Hz}};
    put(row, "k_storage_N_per_mm", l.k_storage_N_per_m * kPerMm);
    put(row, "k_loss_N_per_mm", l.k_loss_N_per_m * kPerMm);
    put(row, "E_storage_Pa", l.E_storage_Pa);
    put(row, "E_loss_Pa", l.E_loss_Pa);
    put(row, "tan_delta", l.tan_delta);
    lines.push_back(row);
  }
  j["lines"] = lines;
  return j;
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

  json summary = result_head("identification");
  const auto& sc = run.recording.sidecar;
  summary["device"] = sc ? sc->device : device_json(run.device);
  summary["firmware_version"] = run.device.firmware_version;
  summary["parameters"] = sc && sc->extra.contains("identification") ? sc->extra["identification"] : json(nullptr);
  summary["recordings"] = json::array({std::string(kSweepStem) + ".csv"});
  const char* end = proto::enum_name(run.program.end);
  summary["run"] = {{"end", run.interrupted ? "interrupted" : end ? end : "unknown"},
                    {"t_device_s", run.program.t_device_s},
                    {"samples", run.recording.size()},
                    {"samples_missing", run.samples_missing},
                    {"interrupted", run.interrupted},
                    {"control_rate_Hz", run.control_rate_Hz}};
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
