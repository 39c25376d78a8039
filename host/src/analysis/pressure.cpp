// SPDX-License-Identifier: Apache-2.0
// Pressure against force, hysteresis and Boyle's law: see palp/analysis/pressure.hpp.
#include "palp/analysis/pressure.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "palp/error.hpp"
#include "indentation_internal.hpp"
#include "number_text.hpp"

namespace palp::analysis {

namespace {

bool all_finite(const Eigen::VectorXd& v) { return v.allFinite(); }

// Linear interpolation of y(x) at xq over samples sorted by x (ties kept in order).
double interpolate(const std::vector<std::pair<double, double>>& xy, double xq) {
  auto it = std::lower_bound(xy.begin(), xy.end(), xq,
                             [](const std::pair<double, double>& a, double v) { return a.first < v; });
  if (it == xy.begin()) return it->second;
  if (it == xy.end()) return xy.back().second;
  const auto& [x1, y1] = *it;
  const auto& [x0, y0] = *(it - 1);
  if (x1 == x0) return y1;
  return y0 + (y1 - y0) * (xq - x0) / (x1 - x0);
}

std::vector<std::pair<double, double>> sorted_pairs(const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
  std::vector<std::pair<double, double>> xy;
  xy.reserve(static_cast<size_t>(x.size()));
  for (Eigen::Index k = 0; k < x.size(); ++k) xy.emplace_back(x[k], y[k]);
  std::stable_sort(xy.begin(), xy.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  return xy;
}

void require_positive(double v, const char* what) {
  if (!std::isfinite(v) || v <= 0.0)
    throw ConfigError(std::string(what) + " must be a finite number above 0, got " + detail::number_text(v));
}

}  // namespace

LineFit fit_line(const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
  if (x.size() != y.size())
    throw ConfigError("fit_line: x has " + std::to_string(x.size()) + " values, y has " +
                      std::to_string(y.size()));
  if (!all_finite(x) || !all_finite(y)) throw ConfigError("fit_line: a value is NaN or infinite");
  LineFit f;
  f.n = static_cast<int>(x.size());
  auto absent = [&](const std::string& why) {
    for (Value* v : {&f.slope, &f.intercept, &f.slope_se, &f.intercept_se, &f.r2})
      *v = Value::absent(why);
    return f;
  };
  if (f.n < 3) return absent("a line needs at least 3 samples, got " + std::to_string(f.n));
  const double mx = x.mean(), my = y.mean();
  const Eigen::ArrayXd dx = x.array() - mx, dy = y.array() - my;
  const double sxx = (dx * dx).sum(), sxy = (dx * dy).sum(), syy = (dy * dy).sum();
  if (!(sxx > 0.0) || sxx <= 1e-24 * static_cast<double>(f.n) * (mx * mx + 1.0))
    return absent("the force does not vary over the samples");
  const double slope = sxy / sxx, intercept = my - slope * mx;
  const double rss = std::max(0.0, (dy - slope * dx).square().sum());
  const double s2 = rss / (f.n - 2);
  f.slope = Value::of(slope);
  f.intercept = Value::of(intercept);
  f.slope_se = Value::of(std::sqrt(s2 / sxx));
  f.intercept_se = Value::of(std::sqrt(s2 * (1.0 / f.n + mx * mx / sxx)));
  f.r2 = syy > 0.0 ? Value::of(1.0 - rss / syy)
                   : Value::absent("the pressure does not vary over the samples");
  return f;
}

PressureHysteresis pressure_hysteresis(const Eigen::VectorXd& load_F, const Eigen::VectorXd& load_p,
                                       const Eigen::VectorXd& unload_F, const Eigen::VectorXd& unload_p,
                                       int grid_points) {
  if (load_F.size() != load_p.size() || unload_F.size() != unload_p.size())
    throw ConfigError("pressure_hysteresis: force and pressure differ in length");
  if (!all_finite(load_F) || !all_finite(load_p) || !all_finite(unload_F) || !all_finite(unload_p))
    throw ConfigError("pressure_hysteresis: a value is NaN or infinite");
  if (grid_points < 2) throw ConfigError("pressure_hysteresis: grid_points must be 2 or more");
  PressureHysteresis h;
  auto absent = [&](const std::string& why) {
    h.loop_area_Pa_N = h.ratio = h.max_gap_Pa = Value::absent(why);
    return h;
  };
  if (load_F.size() < 2) return absent("the loading branch has fewer than 2 samples");
  if (unload_F.size() < 2) return absent("the repetition has no unloading branch");
  const double lo = std::max(load_F.minCoeff(), unload_F.minCoeff());
  const double hi = std::min(load_F.maxCoeff(), unload_F.maxCoeff());
  if (!(hi > lo)) return absent("the loading and unloading branches share no force range");
  const auto L = sorted_pairs(load_F, load_p), U = sorted_pairs(unload_F, unload_p);
  double area = 0.0, gap = 0.0, prev = 0.0;
  const double step = (hi - lo) / (grid_points - 1);
  for (int k = 0; k < grid_points; ++k) {
    const double F = lo + step * k;
    const double d = interpolate(U, F) - interpolate(L, F);
    if (k > 0) area += 0.5 * (d + prev) * step;
    prev = d;
    gap = std::max(gap, std::abs(d));
  }
  const double p_range = load_p.maxCoeff() - load_p.minCoeff();
  h.loop_area_Pa_N = Value::of(area);
  h.max_gap_Pa = Value::of(gap);
  h.ratio = p_range > 0.0 ? Value::of(area / ((hi - lo) * p_range))
                          : Value::absent("the pressure does not vary on the loading branch");
  return h;
}

PressureResult analyze_pressure(const Curve& c, const Eigen::MatrixXd& p_Pa,
                                const IndentationParams& p, double contact_z_m) {
  validate(c, p);
  if (p_Pa.rows() != c.z_m.size())
    throw ConfigError("pressure: " + std::to_string(p_Pa.rows()) + " pressure rows for " +
                      std::to_string(c.z_m.size()) + " samples");
  if (!p_Pa.allFinite()) throw DataError("pressure: a pressure is NaN or infinite");
  if (!std::isfinite(contact_z_m)) throw ConfigError("pressure: the contact point is not finite");
  const Eigen::VectorXd Fo = object_force_N(c, p, contact_z_m);

  PressureResult res;
  res.contact_z_m = contact_z_m;
  struct Rep { std::vector<int> load, unload; };
  std::vector<Rep> reps;
  for (auto [begin, end] : detail::repetitions(c)) {
    Curve one;
    one.z_m = c.z_m.segment(begin, end - begin);
    one.i_A = c.i_A.segment(begin, end - begin);
    const Branches br = loading_branch(one);
    Rep r;
    for (int k : br.loading)
      if (c.i_A[begin + k] >= p.contact_current_A) r.load.push_back(begin + k);
    for (int k : br.unloading)
      if (c.i_A[begin + k] >= p.contact_current_A) r.unload.push_back(begin + k);
    res.n_loading += static_cast<int>(r.load.size());
    reps.push_back(std::move(r));
  }
  if (res.n_loading == 0)
    throw DataError("no contact: no loading sample reaches the contact current I_c = " +
                      detail::number_text(p.contact_current_A) + " A");

  auto gather = [&](const std::vector<int>& idx, Eigen::Index col, Eigen::VectorXd& F, Eigen::VectorXd& P) {
    F.resize(static_cast<Eigen::Index>(idx.size()));
    P.resize(F.size());
    for (size_t k = 0; k < idx.size(); ++k) {
      F[static_cast<Eigen::Index>(k)] = Fo[idx[k]];
      P[static_cast<Eigen::Index>(k)] = p_Pa(idx[k], col);
    }
  };
  for (Eigen::Index ch = 0; ch < p_Pa.cols(); ++ch) {
    ChannelPressure out;
    out.channel = static_cast<int>(ch) + 1;
    std::vector<int> all;
    for (const Rep& r : reps) all.insert(all.end(), r.load.begin(), r.load.end());
    Eigen::VectorXd F, P;
    gather(all, ch, F, P);
    out.fit = fit_line(F, P);
    std::vector<Value> rises, ratios;
    for (const Rep& r : reps) {
      Eigen::VectorXd lF, lP, uF, uP;
      gather(r.load, ch, lF, lP);
      gather(r.unload, ch, uF, uP);
      out.hysteresis.push_back(pressure_hysteresis(lF, lP, uF, uP));
      ratios.push_back(out.hysteresis.back().ratio);
      if (lF.size() >= 2) {
        Eigen::Index peak = 0;
        lF.maxCoeff(&peak);
        rises.push_back(Value::of(lP[peak] - lP[0]));
      } else {
        rises.push_back(Value::absent("fewer than 2 loading samples in contact"));
      }
    }
    const MeanSd rise = mean_sd(rises);
    out.rise_Pa = rise.mean;
    out.rise_sd_Pa = rise.sd;
    out.hysteresis_ratio_mean = mean_sd(ratios).mean;
    res.channels.push_back(std::move(out));
  }
  return res;
}

double enclosed_volume_m3(const ChannelGeometry& g) {
  require_positive(g.channel_diameter_m, "channel diameter");
  require_positive(g.channel_length_m, "channel length");
  if (!std::isfinite(g.tube_length_m) || g.tube_length_m < 0.0)
    throw ConfigError("tube length must be a finite number of 0 or more, got " + detail::number_text(g.tube_length_m));
  if (g.tube_length_m > 0.0) require_positive(g.tube_bore_m, "tube bore");
  const double q = std::numbers::pi / 4.0;
  return q * (g.channel_diameter_m * g.channel_diameter_m * g.channel_length_m +
              (g.tube_length_m > 0.0 ? g.tube_bore_m * g.tube_bore_m * g.tube_length_m : 0.0));
}

BoyleResult boyle_volume_change(double V1_m3, double dP_Pa, double ambient_Pa, double gamma) {
  require_positive(V1_m3, "enclosed volume");
  require_positive(ambient_Pa, "ambient pressure");
  if (!std::isfinite(dP_Pa)) throw ConfigError("pressure change must be a finite number");
  if (!std::isfinite(gamma) || gamma <= 1.0)
    throw ConfigError("heat capacity ratio must be above 1, got " + detail::number_text(gamma));
  const double P2 = ambient_Pa + dP_Pa;
  if (!(P2 > 0.0))
    throw ConfigError("pressure change " + detail::number_text(dP_Pa) + " Pa takes the absolute pressure to " +
                      detail::number_text(P2) + " Pa (must stay above 0)");
  BoyleResult b;
  b.V1_m3 = V1_m3;
  b.P1_Pa = ambient_Pa;
  b.P2_Pa = P2;
  // 1 - P1/P2 = dP/P2: the difference form keeps full precision for small rises
  b.dV_isothermal_m3 = V1_m3 * (dP_Pa / P2);
  b.dV_adiabatic_m3 = 0.0 - V1_m3 * std::expm1(std::log(ambient_Pa / P2) / gamma);  // +0, not -0
  return b;
}

}  // namespace palp::analysis
