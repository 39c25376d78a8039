// SPDX-License-Identifier: Apache-2.0
// The lab-unit JSON of result.hpp: the analysed numbers with the keys, the parameters,
// the experiment's settings.
#include <algorithm>
#include <charconv>
#include <iterator>
#include <vector>
#include <cmath>
#include <string>

#include "experiment_common.hpp"
#include "format/field_table.hpp"
#include "palp/protocol/messages.hpp"
#include "palp/result.hpp"

namespace palp {

namespace {

using nlohmann::json;
using analysis::Value;

using format::kMm;
using format::kNPerMm;

/// key = value * scale, or null with key_reason.
void put(json& j, const std::string& key, const Value& v, double scale) {
  if (v.value) {
    j[key] = *v.value * scale;
  } else {
    j[key] = nullptr;
    j[key + "_reason"] = v.reason.empty() ? "not computed" : v.reason;
  }
}

/// A fit's parameter by name, with its standard error.
struct Param {
  Value value, se;
};
Param fit_param(const std::optional<analysis::ModelFit>& fit, const std::string& why_absent,
                const std::string& name) {
  if (!fit) return {Value::absent(why_absent), Value::absent(why_absent)};
  for (std::size_t k = 0; k < fit->names.size(); ++k) {
    if (fit->names[k] != name) continue;
    const auto i = static_cast<Eigen::Index>(k);
    const double se = fit->se.size() > i ? fit->se[i] : NAN;
    return {Value::of(fit->params[i]),
            std::isfinite(se) ? Value::of(se) : Value::absent("the fit gives no standard error")};
  }
  return {Value::absent("the fit has no " + name), Value::absent("the fit has no " + name)};
}

Value fit_r2(const std::optional<analysis::ModelFit>& fit, const std::string& why_absent) {
  return fit ? Value::of(fit->r2) : Value::absent(why_absent);
}

/// Mean/s.d. over repetitions of one model parameter, from each repetition's own fit.
analysis::MeanSd per_rep_param(const analysis::RepetitionSummary& reps,
                               std::optional<analysis::ModelFit> analysis::IndentationResult::*fit,
                               const std::string& reason_field_hint, const std::string& name) {
  std::vector<Value> v;
  for (const auto& r : reps.per_rep) v.push_back(fit_param(r.*fit, reason_field_hint, name).value);
  return analysis::mean_sd(v);
}

void put_sd(json& j, const std::string& key, const Value& sd, double scale) {
  put(j, key + "_sd", sd.value || !sd.reason.empty() ? sd : Value::absent("no repetitions"), scale);
}

using format::Field;
using format::Need;

// result.json's "parameters" (IndentationSettings) and "parameters.analysis" (IndentationParams,
// also palpctl's "params"); bias_force_N (derived), thickness_mm with bonding and force_noise_N
// (written only when given) by hand. The keys the first result.json reader did not read are
// optional.
const Field<IndentationSettings> kSettingsFields[] = {
    {"start_A", &IndentationSettings::start_A},
    {"stop_A", &IndentationSettings::stop_A},
    {"step_A", &IndentationSettings::step_A},
    {"dwell_s", &IndentationSettings::dwell_s},
    {"reps", &IndentationSettings::repetitions},
    {"unload", &IndentationSettings::unload, 1.0, Need::optional},
    {"displacement_limit_mm", &IndentationSettings::displacement_limit_m, kMm},
    {"rate_Hz", &IndentationSettings::stream_rate_Hz},
    {"zero_pressure", &IndentationSettings::zero_pressure, 1.0, Need::optional},
    {"zero_pressure_s", &IndentationSettings::zero_pressure_s, 1.0, Need::optional},
    {"settle_s", &IndentationSettings::settle_s, 1.0, Need::optional},
};
using IP = analysis::IndentationParams;
const Field<IP> kParamsFields[] = {
    {"kf_N_per_A", &IP::force_constant_N_per_A},
    {"ic_A", &IP::contact_current_A},
    {"kv_N_per_mm", &IP::spring_N_per_m, kNPerMm},
    {"tip_radius_mm", &IP::tip_radius_m, kMm},
    {"poisson", &IP::poisson},
    {"bias_current_A", &IP::bias_current_A},
    {"window_lo_mm", &IP::window_lo_m, kMm},
    {"window_hi_mm", &IP::window_hi_m, kMm},
    {"local_half_width_mm", &IP::local_half_width_m, kMm},
    {"min_points", &IP::min_points, 1.0, Need::optional},
    {"tangent_depths_mm", &IP::tangent_depths_m, kMm, Need::optional},
};

constexpr const char* kModelFree = "model-free: no fit standard error (see the _sd over repetitions)";

}  // namespace

json indentation_params_json(const analysis::IndentationParams& p) {
  json j;
  format::write_fields(j, p, kParamsFields);
  j["bias_force_N"] = p.force_constant_N_per_A * (p.bias_current_A - p.contact_current_A);
  if (p.thickness) {
    j["thickness_mm"] = p.thickness->thickness_m * kMm;
    j["bonding"] = p.thickness->bonding == analysis::Bonding::unbonded ? "unbonded" : "bonded";
  } else {
    j["thickness_mm"] = nullptr;
    j["thickness_mm_reason"] = "no finite-thickness correction asked for";
  }
  if (p.force_noise_N) j["force_noise_N"] = *p.force_noise_N;
  return j;
}

json indentation_summary_json(const analysis::IndentationResult& r,
                              const analysis::RepetitionSummary* reps,
                              const analysis::IndentationParams& params) {
  json j;
  j["params"] = indentation_params_json(params);
  const std::string lin_why = r.linear_reason.empty() ? r.fit_reason : r.linear_reason;
  const std::string hz_why = r.hertz_reason.empty() ? r.fit_reason : r.hertz_reason;
  const std::string sn_why = r.sneddon_reason.empty() ? r.fit_reason : r.sneddon_reason;

  // the contact point (a z in the recording's frame) of the chosen model
  put(j, "contact_point_mm", r.contact_z_m, kMm);
  const analysis::ModelFit* chosen = analysis::chosen_fit(r);
  put(j, "contact_point_mm_se",
      chosen ? Value::of(chosen->contact_z_se_m) : Value::absent(r.contact_z_m.reason), kMm);
  if (reps) put_sd(j, "contact_point_mm", reps->contact_z_m.sd, kMm);

  struct ModelKey {
    const char* value_key;
    const char* r2_key;
    const char* aic_key;
    const std::optional<analysis::ModelFit>& fit;
    std::optional<analysis::ModelFit> analysis::IndentationResult::*member;
    const std::string& why;
    const char* param;
    double scale;
  };
  const ModelKey models[] = {
      {"k_linear_N_per_mm", "r2_linear", "aic_linear", r.linear, &analysis::IndentationResult::linear,
       lin_why, "k_N_per_m", kNPerMm},
      {"E_star_hertz_Pa", "r2_hertz", "aic_hertz", r.hertz, &analysis::IndentationResult::hertz, hz_why,
       "Estar_Pa", 1.0},
      {"E_star_sneddon_Pa", "r2_sneddon", "aic_sneddon", r.sneddon,
       &analysis::IndentationResult::sneddon, sn_why, "Estar_Pa", 1.0},
  };
  for (const auto& m : models) {
    const Param p = fit_param(m.fit, m.why, m.param);
    put(j, m.value_key, p.value, m.scale);
    put(j, std::string(m.value_key) + "_se", p.se, m.scale);
    if (reps) {
      const auto s = per_rep_param(*reps, m.member, "this repetition has no such fit", m.param);
      put_sd(j, m.value_key, s.sd, m.scale);
    }
    if (m.param == std::string("Estar_Pa")) {  // E = E* (1 - nu^2), with its se and sd
      const double e_of_estar = 1.0 - params.poisson * params.poisson;
      const std::string model = m.member == &analysis::IndentationResult::hertz ? "hertz" : "sneddon";
      const std::string key = "E_" + model + "_Pa";
      put(j, key, p.value, e_of_estar);
      put(j, key + "_se", p.se, e_of_estar);
      if (reps) {
        const auto s = per_rep_param(*reps, m.member, "this repetition has no such fit", m.param);
        put_sd(j, key, s.sd, e_of_estar);
      }
    }
    put(j, m.r2_key, fit_r2(m.fit, m.why), 1.0);
    put(j, m.aic_key, m.fit ? Value::of(m.fit->aic) : Value::absent(m.why), 1.0);
  }
  if (r.chosen) {
    j["model_by_aic"] = analysis::model_name(*r.chosen);
  } else {
    j["model_by_aic"] = nullptr;
    j["model_by_aic_reason"] = r.fit_reason.empty() ? "no model could be fitted" : r.fit_reason;
  }

  struct Descriptor {
    const char* key;
    const Value& value;
    const analysis::RepetitionSummary::Stat* stat;
    double scale;
  };
  const Descriptor descriptors[] = {
      {"delta0_mm", r.delta0_m, reps ? &reps->delta0_m : nullptr, kMm},
      {"k_tangent_N_per_mm", r.k_tangent_at_delta0_N_per_m,
       reps ? &reps->k_tangent_at_delta0_N_per_m : nullptr, kNPerMm},
      {"k_fd_N_per_mm", r.k_fd_N_per_m, reps ? &reps->k_fd_N_per_m : nullptr, kNPerMm},
      {"k_ls_window_N_per_mm", r.k_window_N_per_m, reps ? &reps->k_window_N_per_m : nullptr, kNPerMm},
      {"k_fd_paper_N_per_mm", r.k_fd_paper_N_per_m, reps ? &reps->k_fd_paper_N_per_m : nullptr,
       kNPerMm},
  };
  const analysis::DerivedSe se = analysis::derived_se(r);
  const Value model_free = Value::absent(kModelFree);
  const Value* descriptor_se[] = {&se.delta0_m, &se.k_tangent_at_delta0_N_per_m, &model_free,
                                  &model_free, &model_free};
  for (std::size_t k = 0; k < std::size(descriptors); ++k) {
    const auto& d = descriptors[k];
    put(j, d.key, d.value, d.scale);
    put(j, std::string(d.key) + "_se", *descriptor_se[k], d.scale);
    if (d.stat) put_sd(j, d.key, d.stat->sd, d.scale);
  }
  json at = json::object(), at_sd = json::object(), at_se = json::object();
  for (std::size_t k = 0; k < r.tangent_depths_m.size() && k < r.k_tangent_N_per_m.size(); ++k) {
    const std::string key = experiment::depth_key(r.tangent_depths_m[k]);
    put(at, key, r.k_tangent_N_per_m[k], kNPerMm);
    put(at_se, key, k < se.k_tangent_N_per_m.size() ? se.k_tangent_N_per_m[k] : Value::absent("no model fitted"), kNPerMm);
    if (reps && k < reps->k_tangent_N_per_m.size())
      put(at_sd, key, reps->k_tangent_N_per_m[k].sd, kNPerMm);
  }
  j["k_at_depth_N_per_mm"] = at;
  j["k_at_depth_N_per_mm_se"] = at_se;
  if (reps) j["k_at_depth_N_per_mm_sd"] = at_sd;

  j["F0_N"] = r.F0_N;
  j["has_baseline"] = r.has_baseline;
  j["n_loading"] = r.n_loading;
  j["n_unloading"] = r.n_unloading;
  if (reps) j["repetitions"] = reps->per_rep.size();
  return j;
}

json pressure_summary_json(const analysis::PressureResult& pr) {
  json j = {{"contact_point_mm", pr.contact_z_m * kMm}, {"n_loading", pr.n_loading}};
  json arr = json::array();
  for (const analysis::ChannelPressure& cp : pr.channels) {
    json ch = {{"channel", cp.channel}};
    put(ch, "slope_Pa_per_N", cp.fit.slope, 1.0);
    put(ch, "slope_Pa_per_N_se", cp.fit.slope_se, 1.0);
    put(ch, "intercept_Pa", cp.fit.intercept, 1.0);
    put(ch, "r2", cp.fit.r2, 1.0);
    put(ch, "rise_Pa", cp.rise_Pa, 1.0);
    put(ch, "rise_Pa_sd", cp.rise_sd_Pa, 1.0);
    put(ch, "hysteresis_ratio", cp.hysteresis_ratio_mean, 1.0);
    json per = json::array();
    for (const auto& h : cp.hysteresis) {
      json e = json::object();
      put(e, "loop_area_Pa_N", h.loop_area_Pa_N, 1.0);
      put(e, "ratio", h.ratio, 1.0);
      put(e, "max_gap_Pa", h.max_gap_Pa, 1.0);
      per.push_back(e);
    }
    ch["hysteresis_per_rep"] = per;
    arr.push_back(ch);
  }
  j["channels"] = arr;
  return j;
}

json indentation_settings_json(const IndentationSettings& s) {
  json j;
  format::write_fields(j, s, kSettingsFields);
  j["analysis"] = indentation_params_json(s.analysis);
  return j;
}

IndentationSettings indentation_settings_from_json(const json& j, const std::string& where) {
  // result.json's messages: "missing key \"parameters.analysis.poisson\"", "\"parameters.reps\" is
  // not a number"
  const format::JsonSource src(j, where, format::Naming::dotted_path);
  IndentationSettings s;
  format::read_fields(src, s, kSettingsFields);
  const format::JsonSource a(src.object("analysis"), where + "analysis.", format::Naming::dotted_path);
  analysis::IndentationParams& p = s.analysis;
  format::read_fields(a, p, kParamsFields);
  if (a.has("thickness_mm"))
    p.thickness = analysis::Thickness{format::from_file(a.number("thickness_mm", {}), kMm),
                                      a.has("bonding") && a.text("bonding") == "unbonded"
                                          ? analysis::Bonding::unbonded
                                          : analysis::Bonding::bonded};
  if (a.has("force_noise_N")) p.force_noise_N = a.number("force_noise_N", {});
  return s;
}

}  // namespace palp
