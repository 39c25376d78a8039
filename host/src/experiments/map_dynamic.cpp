// SPDX-License-Identifier: Apache-2.0
// Viscoelastic maps (map_dynamic.hpp): a point's dynamic values from its identification and its
// indentation, map.json's keys for them, the grids, and the step map_plan runs after the ramp.
#include "palp/map_dynamic.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "format/field_table.hpp"
#include "map_dynamic_step.hpp"
#include "analysis/number_text.hpp"
#include "palp/analysis/dynamics.hpp"
#include "palp/error.hpp"
#include "palp/identification_result.hpp"
#include "palp/map.hpp"

namespace palp {

namespace {

namespace an = analysis;
using nlohmann::json;

/// The multisine a dynamic map runs at each point, behind this one function:
/// contact_multisine_fast (identification.hpp: 16 s, 2.25-39.75 Hz, 0.03 A true peak).
IdentificationSettings map_multisine() {
  return IdentificationSettings::preset(IdentificationPreset::contact_multisine_fast);
}

std::optional<double> finite_or_none(double v) {
  return std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
}

void add_reason(std::string& to, const std::string& why) {
  if (!why.empty()) to += (to.empty() ? "" : "; ") + why;
}

/// The point's values and the analysis its result.json holds (sweep_summary_json, with the
/// decomposition and the moduli when the indentation gives k_o and delta0).
struct Analysed {
  DynamicPoint point;
  json analysis;  ///< null when the run has no fit
};

void analyse_with_indentation(const IdentificationRun& run, const an::IndentationResult* ind,
                              const an::IndentationParams& params, Analysed& out);

/// A point's values; what the analysis refuses (a fit without a positive zeta, a line with
/// G = 0: ConfigError) leaves the rest absent with its reason instead of stopping the map.
Analysed analyse(const IdentificationRun& run, const an::IndentationResult* ind,
                 const an::IndentationParams& params) {
  Analysed out;
  DynamicPoint& d = out.point;
  if (!run.fit || !run.frf) {
    d.reason = run.analysis_reason.empty() ? "the identification gave no fit" : run.analysis_reason;
    return out;
  }
  const an::SecondOrderFit& fit = *run.fit;
  out.analysis = sweep_summary_json(*run.frf, fit);
  d.omega_n_rad_per_s = finite_or_none(fit.omega_n_rad_per_s);
  d.omega_n_rad_per_s_se = finite_or_none(fit.omega_n_rad_per_s_se);
  d.zeta = finite_or_none(fit.zeta);
  d.zeta_se = finite_or_none(fit.zeta_se);
  if (!fit.adequate)
    add_reason(d.reason,
               "the second-order model is not adequate (normalised cost above its limit)");
  try {
    analyse_with_indentation(run, ind, params, out);
  } catch (const ConfigError& e) {
    add_reason(d.reason, e.what());
  }
  return out;
}

/// m_eff, b_o (with the indentation's k_o) and the moduli (with its delta0) into `out`.
void analyse_with_indentation(const IdentificationRun& run, const an::IndentationResult* ind,
                              const an::IndentationParams& params, Analysed& out) {
  const an::SecondOrderFit& fit = *run.fit;
  DynamicPoint& d = out.point;
  const an::InstrumentDynamics& inst = run.settings.instrument;
  if (ind == nullptr || !ind->k_tangent_at_delta0_N_per_m.value ||
      *ind->k_tangent_at_delta0_N_per_m.value <= 0) {
    add_reason(d.reason, "no static k_o at the bias: " +
                             (ind == nullptr ? std::string("the indentation was not analysed")
                                             : ind->k_tangent_at_delta0_N_per_m.reason));
  } else {
    const an::DerivedSe se = an::derived_se(*ind);
    const double k_o = *ind->k_tangent_at_delta0_N_per_m.value;
    const an::Decomposition dec =
        an::decompose(fit, k_o, inst, se.k_tangent_at_delta0_N_per_m.value.value_or(0));
    out.analysis.update(decomposition_json(dec));
    d.m_eff_kg = dec.m_eff_kg;
    d.b_o_N_s_per_m = dec.b_o_N_s_per_m;
    if (se.k_tangent_at_delta0_N_per_m.value) {
      d.m_eff_kg_se = dec.m_eff_kg_se;
      d.b_o_N_s_per_m_se = dec.b_o_N_s_per_m_se;
    } else {
      add_reason(d.reason, "no standard error of k_o: " + se.k_tangent_at_delta0_N_per_m.reason);
    }
  }
  if (ind == nullptr || !ind->delta0_m.value || *ind->delta0_m.value <= 0 ||
      run.frf->lines.empty()) {
    add_reason(d.reason,
               "no moduli: " + (ind == nullptr || ind->delta0_m.value ? std::string("no delta0")
                                                                      : ind->delta0_m.reason));
    return;
  }
  const an::Viscoelastic v =
      an::viscoelastic_from(run.frf->lines, inst, *ind->delta0_m.value, params.tip_radius_m);
  out.analysis["viscoelastic"] = viscoelastic_json(v);
  // the band's mean moduli; per line sigma(Re, Im of 1/G) = sigma_G / |G|^2, over 2a
  double E1 = 0, E2 = 0, var = 0;
  bool noise = true;
  for (std::size_t k = 0; k < v.lines.size(); ++k) {
    E1 += v.lines[k].E_storage_Pa;
    E2 += v.lines[k].E_loss_Pa;
    const an::FrfLine& l = run.frf->lines[k];
    const double s = l.sigma_m_per_N / std::norm(l.G_m_per_N) / (2.0 * v.contact_radius_m);
    noise = noise && l.sigma_m_per_N > 0;
    var += s * s;
  }
  const double n = static_cast<double>(v.lines.size());
  d.E_storage_Pa = finite_or_none(E1 / n);
  d.E_loss_Pa = finite_or_none(E2 / n);
  if (noise) {
    d.E_storage_Pa_se = d.E_loss_Pa_se = finite_or_none(std::sqrt(var) / n);
  } else {
    add_reason(d.reason, "no standard error of the moduli: the lines carry no noise estimate");
  }
  if (v.flagged) add_reason(d.reason, v.flag_reason);
}

}  // namespace

IdentificationSettings map_dynamic_settings(const IndentationSettings& indentation) {
  IdentificationSettings s = map_multisine();
  const an::IndentationParams& p = indentation.analysis;
  s.bias_A = p.bias_current_A;
  s.contact_current_A = p.contact_current_A;
  s.frf.force_constant_N_per_A = p.force_constant_N_per_A;
  s.instrument.k_v_N_per_m = p.spring_N_per_m;
  return s;
}

DynamicPoint dynamic_point_of(const IdentificationRun& run,
                              const an::IndentationResult* indentation,
                              const an::IndentationParams& params) {
  return analyse(run, indentation, params).point;
}

DynamicPoint reanalyse_dynamic_point(const LoadedResult& r,
                                     const an::IndentationResult* indentation,
                                     const an::IndentationParams& params) {
  if (r.experiment != "identification" || r.recordings.empty())
    throw ConfigError(r.dir.string() + ": not an identification result (experiment \"" +
                      r.experiment + "\")");
  IdentificationRun run = identification_run_of(r.recordings.front().second);
  analyze_identification(run);
  return dynamic_point_of(run, indentation, params);
}

const std::vector<DynamicQuantity>& dynamic_quantities() {
  static const std::vector<DynamicQuantity> q = {
      {"omega_n_rad_per_s", "ω_n (rad/s)", "rad/s", &DynamicPoint::omega_n_rad_per_s,
       &DynamicPoint::omega_n_rad_per_s_se},
      {"zeta", "ζ", "1", &DynamicPoint::zeta, &DynamicPoint::zeta_se},
      {"m_eff_kg", "m_eff (kg)", "kg", &DynamicPoint::m_eff_kg, &DynamicPoint::m_eff_kg_se},
      {"b_o_N_s_per_m", "b_o (N s/m)", "N s/m", &DynamicPoint::b_o_N_s_per_m,
       &DynamicPoint::b_o_N_s_per_m_se},
      {"E_storage_Pa", "E′ (Pa)", "Pa", &DynamicPoint::E_storage_Pa,
       &DynamicPoint::E_storage_Pa_se},
      {"E_loss_Pa", "E″ (Pa)", "Pa", &DynamicPoint::E_loss_Pa, &DynamicPoint::E_loss_Pa_se},
  };
  return q;
}

void write_dynamic_point(json& j, const MapPoint& p) {
  const DynamicPoint& d = p.dynamic;
  if (p.dynamic_dir.empty() && d.reason.empty()) return;  // not a dynamic point
  j["dynamic_dir"] = p.dynamic_dir;
  const char* why = d.reason.empty() ? "not identified" : d.reason.c_str();
  for (const DynamicQuantity& q : dynamic_quantities()) {
    format::put_or_null(j, q.key, d.*q.value, why);
    format::put_or_null(j, std::string(q.key) + "_se", d.*q.se, why);
  }
  j["dynamic_reason"] = d.reason;
}

void read_dynamic_point(const json& j, const std::string& where, MapPoint& p) {
  auto number = [&](const std::string& key) -> std::optional<double> {
    const auto f = j.find(key);
    if (f == j.end() || f->is_null()) return std::nullopt;
    if (!f->is_number()) throw ConfigError(where + ": \"" + key + "\" must be a number or null");
    return f->get<double>();
  };
  auto text = [&](const char* key) {
    const auto f = j.find(key);
    if (f == j.end() || f->is_null()) return std::string();
    if (!f->is_string()) throw ConfigError(where + ": \"" + key + "\" must be a string");
    return f->get<std::string>();
  };
  p.dynamic_dir = text("dynamic_dir");
  p.dynamic.reason = text("dynamic_reason");
  for (const DynamicQuantity& q : dynamic_quantities()) {
    p.dynamic.*q.value = number(q.key);
    p.dynamic.*q.se = number(std::string(q.key) + "_se");
  }
}

MapDynamicGrids map_dynamic_grids(const StiffnessMap& m) {
  MapDynamicGrids g;
  g.rows = m.rows;
  g.columns = m.columns;
  const std::size_t n = static_cast<std::size_t>(std::max(0, m.rows * m.columns));
  g.value.assign(dynamic_quantities().size(), std::vector<std::optional<double>>(n));
  g.se = g.value;
  for (const MapPoint& p : m.points) {
    if (p.row < 1 || p.row > m.rows || p.column < 1 || p.column > m.columns) continue;
    if (!p.dynamic_dir.empty()) ++g.points_identified;
    const auto at = static_cast<std::size_t>((p.row - 1) * m.columns + p.column - 1);
    for (std::size_t k = 0; k < dynamic_quantities().size(); ++k) {
      g.value[k][at] = p.dynamic.*dynamic_quantities()[k].value;
      g.se[k][at] = p.dynamic.*dynamic_quantities()[k].se;
    }
  }
  return g;
}

namespace detail {

void check_dynamic_settings(const IdentificationSettings& s,
                            const IndentationSettings& indentation) {
  s.validate();
  if (!s.in_contact)
    throw ConfigError("dynamic map: the identification must be in contact (in_contact)");
  const double I0 = indentation.analysis.bias_current_A;
  if (std::abs(s.bias_A - I0) > 1e-9)
    throw ConfigError(
        "dynamic map: the identification's bias " + analysis::detail::number_text(s.bias_A) +
        " A is not the indentation analysis' I_0 " + analysis::detail::number_text(I0) +
        " A (k_o and delta0 would be at another operating point)");
}

bool identify_map_point(Probe& probe, const IdentificationSettings& s,
                        const IndentationRun& indentation, const std::filesystem::path& map_dir,
                        MapPoint& p, const std::function<bool()>& cancelled) {
  IdentificationRun run = identify(probe, s, {}, cancelled);
  if (run.interrupted) return false;
  const Analysed a = analyse(run, indentation.analysis ? &*indentation.analysis : nullptr,
                             indentation.settings.analysis);
  p.dynamic_dir = dynamic_dir_of(p.result_dir);
  p.dynamic = a.point;
  write_identification_result(map_dir / p.dynamic_dir, run, a.analysis, Overwrite::yes);
  return true;
}

std::string dynamic_dir_of(const std::string& result_dir) { return result_dir + "_dynamic"; }

}  // namespace detail

}  // namespace palp
