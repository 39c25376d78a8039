// SPDX-License-Identifier: Apache-2.0
// The identification section (sections.hpp), the paper's Fig. 4(d): Bode magnitude and phase of
// the measured response (frf.csv beside result.json) with each line's σ as error bars and the
// fitted second-order model G = 1 / (k − m ω² + j b ω) from result.json's analysis (m_kg,
// b_N_s_per_m, k_N_per_mm); the natural frequency marked. E′(ω), E″(ω) and tan δ when the
// analysis holds "viscoelastic". A table of ω_n, ζ, m, b, k with their s.e., the fit's cost,
// the instrument's free-air m_v and b_v and the contact decomposition when present.
//
// Magnitude in dB re 1 m/N (20 log10 |G|); a line's band is 20 log10(|G| ± σ) (σ: the s.d. of
// Re G and of Im G each), its phase band ± σ/|G| rad. Phase unwrapped from the first line.
#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "palp/analysis/frf_table.hpp"
#include "palp/error.hpp"
#include "palp/identification_result.hpp"
#include "report/section_format.hpp"
#include "report/sections.hpp"
#include "report/vega_build.hpp"

namespace palp::report {

namespace identification_figures {

namespace an = analysis;
using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;
constexpr int kWidth = 560, kHeight = 260;
constexpr int kModelPoints = 300;

struct Model {
  double m_kg = 0, b_N_s_per_m = 0, k_N_per_m = 0;
  std::complex<double> G(double f_Hz) const {
    const double w = 2 * kPi * f_Hz;
    return 1.0 / std::complex<double>(k_N_per_m - m_kg * w * w, b_N_s_per_m * w);
  }
};

double number(const json& a, const char* key) {
  return a.contains(key) && a[key].is_number() ? a[key].get<double>() : std::nan("");
}

std::optional<Model> model_of(const json& a) {
  Model m{number(a, "m_kg"), number(a, "b_N_s_per_m"), number(a, "k_N_per_mm") * 1e3};
  if (!(m.m_kg > 0) || !(m.b_N_s_per_m >= 0) || !(m.k_N_per_m > 0)) return std::nullopt;
  return m;
}

double dB(double mag) { return 20.0 * std::log10(mag); }

// Phases in degrees, unwrapped along the sequence.
std::vector<double> unwrapped_deg(const std::vector<std::complex<double>>& G) {
  std::vector<double> out;
  double previous = 0;
  for (std::size_t k = 0; k < G.size(); ++k) {
    double p = std::arg(G[k]) * 180.0 / kPi;
    if (k > 0) {
      while (p - previous > 180.0) p -= 360.0;
      while (p - previous < -180.0) p += 360.0;
    }
    out.push_back(p);
    previous = p;
  }
  return out;
}

struct Curves {
  std::vector<double> f, mag_dB, lo_dB, hi_dB, mag_m_per_N, sigma, phase, phase_lo, phase_hi;
  std::vector<double> mf, mmag_dB, mphase;  // the model
};

Curves curves_of(const an::Frf& frf, const std::optional<Model>& model) {
  Curves c;
  std::vector<std::complex<double>> G;
  for (const auto& l : frf.lines) G.push_back(l.G_m_per_N);
  c.phase = unwrapped_deg(G);
  for (std::size_t k = 0; k < frf.lines.size(); ++k) {
    const auto& l = frf.lines[k];
    const double mag = std::abs(l.G_m_per_N), s = l.sigma_m_per_N;
    c.f.push_back(l.f_Hz);
    c.mag_m_per_N.push_back(mag);
    c.sigma.push_back(s);
    c.mag_dB.push_back(dB(mag));
    // a band reaching zero magnitude is drawn 40 dB down (the log of 0)
    c.lo_dB.push_back(mag - s > 0 ? dB(mag - s) : dB(mag) - 40.0);
    c.hi_dB.push_back(dB(mag + s));
    const double dphi = mag > 0 ? std::min(180.0, s / mag * 180.0 / kPi) : 0.0;
    c.phase_lo.push_back(c.phase[k] - dphi);
    c.phase_hi.push_back(c.phase[k] + dphi);
  }
  if (model && !c.f.empty()) {
    const double lo = c.f.front() / 1.25, hi = c.f.back() * 1.25;
    std::vector<std::complex<double>> mG;
    for (int k = 0; k <= kModelPoints; ++k) {
      const double f = lo * std::pow(hi / lo, static_cast<double>(k) / kModelPoints);
      c.mf.push_back(f);
      mG.push_back(model->G(f));
      c.mmag_dB.push_back(dB(std::abs(mG.back())));
    }
    c.mphase = unwrapped_deg(mG);
    // each measured phase on the model's branch (a noisy line past resonance would otherwise
    // carry the unwrapping off by 360°)
    for (std::size_t k = 0; k < c.phase.size(); ++k) {
      const double at = c.mphase[static_cast<std::size_t>(
          std::lower_bound(c.mf.begin(), c.mf.end(), c.f[k]) - c.mf.begin())];
      const double shift = 360.0 * std::round((at - c.phase[k]) / 360.0);
      c.phase[k] += shift;
      c.phase_lo[k] += shift;
      c.phase_hi[k] += shift;
    }
  }
  return c;
}

const std::string kMeasured = vega::colour(0), kModel = vega::colour(1);

json bode_base(const Curves& c, const std::string& y_title, vega::Extent y, const json& f_n_Hz) {
  json s = vega::spec(kWidth, kHeight);
  vega::Extent x;
  x.add(c.f);
  x.add(c.mf);
  vega::add_scale(s, vega::log_scale("x", x, vega::Range::width));
  json ys = vega::linear_scale("y", y, vega::Range::height);
  vega::add_scale(s, ys);
  vega::add_scale(s, vega::colour_scale("series", {"measured ± σ", "second-order fit"},
                                        {kMeasured, kModel}));
  vega::add_axes(s, "x", "f (Hz)", "y", y_title);
  s["legends"].push_back(vega::legend("series"));
  if (f_n_Hz.is_number()) {
    const double fn = f_n_Hz.get<double>();
    vega::add_mark(s, vega::vertical_rule("x", fn, {"#555", 1.0, {3, 3}, 0.9}, "f_n_rule"));
  }
  return s;
}

json magnitude_spec(const Curves& c, const json& a) {
  // the axis spans the lines and the model; a σ bar longer than that is clipped
  vega::Extent y;
  y.add(c.mag_dB);
  y.add(c.mmag_dB);
  if (!y.empty()) {
    y.add(y.lo - 6.0);
    y.add(y.hi + 6.0);
  }
  json s = bode_base(c, "|G| (dB re 1 m/N)", y, a.value("f_n_Hz", json()));
  vega::add_data(s, "measured", vega::rows({{"f_Hz", c.f}, {"mag_dB", c.mag_dB}, {"lo_dB", c.lo_dB},
                                            {"hi_dB", c.hi_dB}, {"mag_m_per_N", c.mag_m_per_N},
                                            {"sigma_m_per_N", c.sigma}}));
  vega::add_data(s, "model", vega::rows({{"f_Hz", c.mf}, {"mag_dB", c.mmag_dB}}));
  vega::add_mark(s, vega::error_bars("measured", "x", "f_Hz", "y", "lo_dB", "hi_dB", kMeasured,
                                     "magnitude_sigma"));
  json pts = vega::symbols("measured", "x", "f_Hz", "y", "mag_dB", kMeasured, 18, "circle",
                           "magnitude_points");
  vega::add_tooltip(pts, {{"f (Hz)", "f_Hz"}, {"|G| (m/N)", "mag_m_per_N"},
                          {"σ (m/N)", "sigma_m_per_N"}});
  vega::add_mark(s, std::move(pts));
  vega::add_mark(s, vega::line("model", "x", "f_Hz", "y", "mag_dB", {kModel, 2.0, {}, 1.0},
                               "magnitude_model"));
  std::vector<std::string> lines;
  if (a.contains("f_n_Hz") && a["f_n_Hz"].is_number())
    lines.push_back("f_n = " + format_cell(a, "f_n_Hz") + " Hz (ω_n = " + format_cell(a, "omega_n_rad_per_s") +
                    " ± " + format_cell(a, "omega_n_rad_per_s_se", 1.0, 2) + " rad/s)");
  if (a.contains("zeta") && a["zeta"].is_number())
    lines.push_back("ζ = " + format_cell(a, "zeta") + " ± " + format_cell(a, "zeta_se", 1.0, 2));
  if (!lines.empty()) vega::add_mark(s, vega::corner_text(lines, "top-right", "#222", "fit_text"));
  return s;
}

json phase_spec(const Curves& c, const json& a) {
  vega::Extent y;  // the lines and the model; longer σ bars are clipped
  y.add(c.phase);
  y.add(c.mphase);
  // whole multiples of 45 deg, ticks on each
  vega::Extent snapped;
  if (!y.empty()) {
    snapped.add(std::floor(y.lo / 45.0) * 45.0);
    snapped.add(std::ceil(y.hi / 45.0) * 45.0);
  }
  json s = bode_base(c, "phase (deg)", snapped, a.value("f_n_Hz", json()));
  s["scales"][1]["domain"] = snapped.empty() ? json::array({-180.0, 0.0}) : snapped.domain(0.0);
  s["scales"][1]["nice"] = false;
  json ticks = json::array();
  for (double t = snapped.lo; t <= snapped.hi + 1e-9; t += 45.0) ticks.push_back(t);
  s["axes"][1]["values"] = ticks;
  vega::add_data(s, "measured", vega::rows({{"f_Hz", c.f}, {"phase_deg", c.phase},
                                            {"lo_deg", c.phase_lo}, {"hi_deg", c.phase_hi}}));
  vega::add_data(s, "model", vega::rows({{"f_Hz", c.mf}, {"phase_deg", c.mphase}}));
  vega::add_mark(s, vega::error_bars("measured", "x", "f_Hz", "y", "lo_deg", "hi_deg", kMeasured,
                                     "phase_sigma"));
  json pts = vega::symbols("measured", "x", "f_Hz", "y", "phase_deg", kMeasured, 18, "circle",
                           "phase_points");
  vega::add_tooltip(pts, {{"f (Hz)", "f_Hz"}, {"phase (deg)", "phase_deg"}});
  vega::add_mark(s, std::move(pts));
  vega::add_mark(s, vega::line("model", "x", "f_Hz", "y", "phase_deg", {kModel, 2.0, {}, 1.0},
                               "phase_model"));
  return s;
}

// A line whose noise leaves its contact stiffness k* = 2a (E′ + j E″) uncertain by more than
// this fraction: 1/G's error is about σ/|G|² (N/m), against |k*|.
constexpr double kNoisyFraction = 0.2;

// The relative uncertainty of the contact stiffness at a viscoelastic line (0 when the measured
// line carries no σ or is not in the table; infinite for a zero stiffness).
double moduli_uncertainty(const an::Frf& frf, const an::ViscoelasticLine& v, double a_m) {
  const double k = 2 * a_m * std::hypot(v.E_storage_Pa, v.E_loss_Pa);
  for (const auto& l : frf.lines)
    if (std::abs(l.f_Hz - v.f_Hz) <= 1e-9 * v.f_Hz && std::abs(l.G_m_per_N) > 0) {
      const double sigma_k = l.sigma_m_per_N / std::norm(l.G_m_per_N);
      return k > 0 ? sigma_k / k : std::numeric_limits<double>::infinity();
    }
  return 0.0;
}

json moduli_spec(const an::Viscoelastic& v, const an::Frf& frf) {
  std::vector<double> f, Es, El, tan, noisy;
  vega::Extent x, y, t, y_all, t_all;
  for (const auto& l : v.lines) {
    f.push_back(l.f_Hz);
    Es.push_back(l.E_storage_Pa);
    El.push_back(l.E_loss_Pa);
    tan.push_back(l.tan_delta);
    noisy.push_back(moduli_uncertainty(frf, l, v.contact_radius_m) > kNoisyFraction ? 1.0 : 0.0);
    for (auto* e : {&y_all, &y}) {
      if (e == &y && noisy.back() != 0.0) continue;
      e->add(l.E_storage_Pa);
      e->add(l.E_loss_Pa);
    }
    t_all.add(l.tan_delta);
    if (noisy.back() == 0.0) t.add(l.tan_delta);
  }
  // the axes span the trusted lines (all of them when none is)
  if (y.empty()) y = y_all;
  if (t.empty()) t = t_all;
  x.add(f);
  json s = vega::spec(kWidth, kHeight);
  const json rows = vega::rows({{"f_Hz", f}, {"E_storage_Pa", Es}, {"E_loss_Pa", El},
                                {"tan_delta", tan}, {"noisy", noisy}});
  vega::add_data(s, "moduli", rows);
  vega::add_scale(s, vega::log_scale("x", x, vega::Range::width));
  vega::add_scale(s, vega::linear_scale("y", y, vega::Range::height, true));
  vega::add_scale(s, vega::linear_scale("t", t, vega::Range::height, true));
  const std::vector<std::string> labels = {"E′ (storage)", "E″ (loss)", "tan δ (right axis)"};
  const std::vector<std::string> colours = {vega::colour(0), vega::colour(1), vega::colour(2)};
  vega::add_scale(s, vega::colour_scale("series", labels, colours));
  s["axes"].push_back(vega::axis("x", "bottom", "f (Hz)"));
  s["axes"].push_back(vega::axis("y", "left", "E′, E″ (Pa)", 0, ",d"));  // 120,000
  s["axes"].push_back(vega::axis("t", "right", "tan δ (1)", 0, {}, false));
  s["legends"].push_back(vega::legend("series"));
  const std::pair<const char*, const char*> series[] = {
      {"E_storage_Pa", "y"}, {"E_loss_Pa", "y"}, {"tan_delta", "t"}};
  for (std::size_t k = 0; k < 3; ++k) {
    const std::string field = series[k].first, scale = series[k].second;
    vega::Stroke st{colours[k], 1.8, {}, 1.0};
    if (k == 2) st.dash = {5, 3};
    json line = vega::line("moduli", "x", "f_Hz", scale, field, st, field + "_line");
    line["encode"]["enter"]["defined"] = {{"signal", "!datum.noisy"}};  // broken at noisy lines
    vega::add_mark(s, std::move(line));
    json pts = vega::symbols("moduli", "x", "f_Hz", scale, field, colours[k], 14, "circle",
                             field + "_points");
    pts["encode"]["enter"]["fillOpacity"] = {{"signal", "datum.noisy ? 0 : 0.55"}};
    pts["encode"]["enter"]["strokeOpacity"] = {{"signal", "datum.noisy ? 0.4 : 1"}};
    vega::add_tooltip(pts, {{"f (Hz)", "f_Hz"}, {"E′ (Pa)", "E_storage_Pa"},
                            {"E″ (Pa)", "E_loss_Pa"}, {"tan δ", "tan_delta"}});
    vega::add_mark(s, std::move(pts));
  }
  std::vector<std::string> text = {"δ0 = " + format_number(v.delta0_m * 1e3) + " mm, contact radius a = " +
                                   format_number(v.contact_radius_m * 1e3) + " mm"};
  if (std::count(noisy.begin(), noisy.end(), 1.0) > 0)
    text.push_back("○: noise > " + format_number(kNoisyFraction * 100) +
                   " % of the contact stiffness (not on the lines or axes)");
  if (v.flagged) text.push_back("flagged: " + v.flag_reason);
  vega::add_mark(s, vega::corner_text(text, "bottom-right", v.flagged ? "#b00" : "#222", "moduli_text"));
  return s;
}

std::vector<std::string> row(const json& a, const std::string& quantity, const std::string& unit,
                             const std::string& key, double scale = 1.0) {
  std::string value = format_cell(a, key, scale, 5);
  if (value == "—" && !reason_of(a, key).empty()) value += " (" + reason_of(a, key) + ")";
  return {quantity, unit, value, format_cell(a, key + "_se", scale, 2)};
}

Table parameter_table(const json& a) {
  Table t;
  t.id = "identification-parameters";
  t.title = "Second-order fit and instrument";
  t.columns = {"quantity", "unit", "value", "s.e."};
  t.rows = {{"method", "", format_cell(a, "method"), ""},
            row(a, "lines", "", "lines"),
            row(a, "ω_n", "rad/s", "omega_n_rad_per_s"),
            row(a, "f_n", "Hz", "f_n_Hz"),
            row(a, "ζ", "", "zeta"),
            row(a, "m (fit)", "kg", "m_kg"),
            row(a, "b (fit)", "N s/m", "b_N_s_per_m"),
            row(a, "k (fit)", "N/mm", "k_N_per_mm"),
            row(a, "normalised cost χ²/(2n − 3)", "", "normalized_cost"),
            {"adequate (cost ≤ 4)", "", format_cell(a, "adequate"), ""}};
  if (a.contains("free_air") && a["free_air"].is_object()) {
    const json& fa = a["free_air"];
    t.rows.push_back(row(fa, "free air m_v", "kg", "m_v_kg"));
    t.rows.push_back(row(fa, "free air b_v", "N s/m", "b_v_N_s_per_m"));
    t.rows.push_back(row(fa, "k_v", "N/mm", "kv_N_per_mm"));
  } else if (a.contains("params") && a["params"].is_object()) {
    t.rows.push_back(row(a["params"], "instrument m_v (used)", "kg", "mv_kg"));
    t.rows.push_back(row(a["params"], "instrument b_v (used)", "N s/m", "bv_N_s_per_m"));
  }
  for (const auto& [key, label, unit] : {std::tuple{"k_o_N_per_mm", "k_o (static)", "N/mm"},
                                         std::tuple{"k_eff_N_per_mm", "k_eff", "N/mm"},
                                         std::tuple{"m_eff_kg", "m_eff", "kg"},
                                         std::tuple{"b_total_N_s_per_m", "b_total", "N s/m"},
                                         std::tuple{"b_o_N_s_per_m", "b_o (object)", "N s/m"},
                                         std::tuple{"m_o_kg", "m_o (object)", "kg"}})
    if (a.contains(key)) t.rows.push_back(row(a, label, unit, key));
  t.caption = "From result.json's analysis; s.e. from the fit's covariance (the delta method for "
              "ω_n and ζ). m_v and b_v: the free-air identification's, or the instrument values "
              "the contact analysis subtracted.";
  return t;
}

}  // namespace identification_figures

Section identification_section(const LoadedResult& result) {
  namespace fig = identification_figures;
  const std::string name = (result.dir / kResultFile).string();
  if (result.experiment != "identification")
    throw RecordingError(name, 0, "experiment is \"" + result.experiment + "\", not an identification");
  const auto frf_file = result.dir / "frf.csv";
  if (!std::filesystem::exists(frf_file))
    throw RecordingError(frf_file.string(), 0, "missing: the identification's measured response");
  const analysis::Frf frf = analysis::read_frf_table(frf_file);
  const nlohmann::json a = result.summary.contains("analysis") && result.summary["analysis"].is_object()
                               ? result.summary["analysis"]
                               : nlohmann::json::object();
  const auto model = fig::model_of(a);
  const fig::Curves c = fig::curves_of(frf, model);

  Section s;
  s.id = "identification";
  s.title = "Identification " + result.dir.filename().string();
  s.text = std::to_string(frf.lines.size()) + " lines from " + format_number(frf.lines.front().f_Hz) +
           " to " + format_number(frf.lines.back().f_Hz) + " Hz (" + format_cell(a, "method") + ")." +
           (model ? std::string() : " No second-order fit in result.json: " +
                                        reason_of(result.summary, "analysis") + ".");
  const std::string fit_note = model ? " and the fitted second-order model 1/(k − m ω² + j b ω)" : "";
  s.figures.push_back({"identification-bode-magnitude", "Bode magnitude",
                       "|G| = |Z/F| of each measured line with ± σ" + fit_note +
                           "; dashed: the natural frequency f_n.",
                       fig::magnitude_spec(c, a)});
  s.figures.push_back({"identification-bode-phase", "Bode phase",
                       "Phase of G (the displacement lags the force) with ± σ/|G|" + fit_note + ".",
                       fig::phase_spec(c, a)});
  if (a.contains("viscoelastic") && a["viscoelastic"].is_object()) {
    analysis::Viscoelastic v;
    try {
      v = viscoelastic_from_json(a);
    } catch (const ConfigError& e) {
      throw RecordingError(name, 0, std::string("analysis: ") + e.what());
    }
    s.figures.push_back({"identification-moduli", "Storage and loss moduli",
                         "E′(ω) and E″(ω) from the contact's dynamic stiffness with the instrument's "
                         "m_v, b_v, k_v removed, over the Sneddon contact radius at δ0; tan δ = E″/E′. "
                         "Hollow: lines whose noise σ/|G|² exceeds 20 % of the contact stiffness "
                         "2a |E′ + j E″| (their moduli are mostly noise); the lines and axes leave "
                         "them out.",
                         fig::moduli_spec(v, frf)});
  }
  s.tables.push_back(fig::parameter_table(a));
  return s;
}

}  // namespace palp::report
