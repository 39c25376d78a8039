// SPDX-License-Identifier: Apache-2.0
// Branches, descriptors and the whole quasi-static analysis: see palp/analysis/indentation.hpp.
#include "palp/analysis/indentation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "analysis/indentation_internal.hpp"
#include "palp/error.hpp"
#include "number_text.hpp"

namespace palp::analysis {

namespace {

bool finite_params(const IndentationParams& p) {
  for (double v : {p.force_constant_N_per_A, p.contact_current_A, p.spring_N_per_m, p.tip_radius_m,
                   p.poisson, p.bias_current_A, p.window_lo_m, p.window_hi_m, p.local_half_width_m})
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace

void validate(const Curve& c, const IndentationParams& p) {
  if (c.z_m.size() != c.i_A.size())
    throw ConfigError("indentation curve: z_m has " + std::to_string(c.z_m.size()) +
                      " samples but i_A has " + std::to_string(c.i_A.size()));
  if (c.rep.size() != 0 && c.rep.size() != c.z_m.size())
    throw ConfigError("indentation curve: rep has " + std::to_string(c.rep.size()) +
                      " entries for " + std::to_string(c.z_m.size()) + " samples");
  if (c.i_cmd_A.size() != 0 && c.i_cmd_A.size() != c.z_m.size())
    throw ConfigError("indentation curve: i_cmd_A has " + std::to_string(c.i_cmd_A.size()) +
                      " entries for " + std::to_string(c.z_m.size()) + " samples");
  for (Eigen::Index k = 0; k < c.z_m.size(); ++k) {
    if (!std::isfinite(c.z_m[k]) || !std::isfinite(c.i_A[k]) ||
        (c.i_cmd_A.size() != 0 && !std::isfinite(c.i_cmd_A[k])))
      throw DataError("indentation curve: sample " + std::to_string(k) +
                      " is not finite (z_m = " + detail::number_text(c.z_m[k]) + ", i_A = " + detail::number_text(c.i_A[k]) +
                      (c.i_cmd_A.size() != 0 ? ", i_cmd_A = " + detail::number_text(c.i_cmd_A[k]) : std::string()) +
                      "); remove or repair it before the analysis");
  }
  const auto& tx = p.kf_table_stroke_m;
  const auto& tk = p.kf_table_N_per_A;
  bool table_ok = tx.size() == tk.size() && std::isfinite(p.stroke_origin_z_m);
  for (std::size_t k = 0; table_ok && k < tx.size(); ++k)
    table_ok = std::isfinite(tx[k]) && std::isfinite(tk[k]) && tk[k] > 0.0 && (k == 0 || tx[k] > tx[k - 1]);
  if (!table_ok)
    throw ConfigError("indentation parameters: the K_f table needs as many positions as values, "
                      "positions increasing, every K_f > 0, and a finite stroke origin");
  if (!finite_params(p) || !(p.force_constant_N_per_A > 0.0) || !(p.tip_radius_m > 0.0) ||
      !(p.spring_N_per_m >= 0.0) || !(p.poisson >= 0.0 && p.poisson < 1.0) ||
      !(p.window_hi_m > p.window_lo_m) || !(p.local_half_width_m > 0.0) || p.min_points < 3 ||
      (p.thickness && !(p.thickness->thickness_m > 0.0)) ||
      (p.force_noise_N && !(std::isfinite(*p.force_noise_N) && *p.force_noise_N > 0.0)))
    throw ConfigError("indentation parameters: need finite K_f > 0, R > 0, k_v >= 0, 0 <= nu < 1, "
                      "window_hi_m > window_lo_m, local_half_width_m > 0, min_points >= 3, and a "
                      "positive thickness and force noise when given");
}

double IndentationParams::force_constant_at(double z_m) const {
  const auto& x = kf_table_stroke_m;
  const auto& k = kf_table_N_per_A;
  if (x.empty()) return force_constant_N_per_A;
  const double s = z_m - stroke_origin_z_m;
  if (s <= x.front()) return k.front();
  if (s >= x.back()) return k.back();
  const auto hi = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), s) - x.begin());
  const double w = (s - x[hi - 1]) / (x[hi] - x[hi - 1]);
  return k[hi - 1] + w * (k[hi] - k[hi - 1]);
}

Eigen::VectorXd coil_force_N(const Curve& c, const IndentationParams& p) {
  Eigen::VectorXd F(c.i_A.size());
  for (Eigen::Index k = 0; k < F.size(); ++k)
    F[k] = p.force_constant_at(c.z_m[k]) * (c.i_A[k] - p.contact_current_A);
  return F;
}

Eigen::VectorXd object_force_N(const Curve& c, const IndentationParams& p, double contact_z_m) {
  return coil_force_N(c, p) - p.spring_N_per_m * (c.z_m.array() - contact_z_m).matrix();
}

Branches loading_branch(const Curve& c) {
  Branches b;
  for (auto [begin, end] : detail::repetitions(c)) {
    int peak = begin;
    for (int k = begin; k < end; ++k) if (c.i_A[k] > c.i_A[peak]) peak = k;
    for (int k = begin; k <= peak; ++k) b.loading.push_back(k);
    for (int k = peak + 1; k < end; ++k) b.unloading.push_back(k);
  }
  return b;
}

const char* fit_on_name(FitOn f) { return f == FitOn::plateaus ? "plateaus" : "samples"; }

namespace {

// The fit points of the loading samples idx (rep_of: their repetition ordinals): every sample,
// or one point per run of equal commanded current within a repetition.
detail::FitPoints fit_points(const Curve& c, const detail::FitData& d, const std::vector<int>& idx,
                             const IndentationParams& p) {
  detail::FitPoints f;
  const auto n = d.z_m.size();
  if (p.fit_on == FitOn::samples || c.i_cmd_A.size() == 0) {
    f.z_m = d.z_m;
    f.F_N = d.F_N;
    f.w = Eigen::VectorXd::Ones(n);
    f.szz = f.sff = f.szf = Eigen::VectorXd::Zero(n);
    return f;
  }
  f.on = FitOn::plateaus;
  std::vector<std::pair<Eigen::Index, Eigen::Index>> runs;  // [begin, end) in the loading samples
  for (Eigen::Index k = 0, b = 0; k <= n; ++k) {
    if (k == n || d.rep_of[static_cast<std::size_t>(k)] != d.rep_of[static_cast<std::size_t>(b)] ||
        c.i_cmd_A[idx[static_cast<std::size_t>(k)]] != c.i_cmd_A[idx[static_cast<std::size_t>(b)]]) {
      if (k > b) runs.emplace_back(b, k);
      b = k;
    }
  }
  // a plateau whose probe travels far more than the typical one (the settle onto the specimen
  // at the ramp's start, a slip) enters as its samples: a mean and a slope would not describe it
  std::vector<double> span(runs.size());
  for (std::size_t j = 0; j < runs.size(); ++j) {
    const auto z = d.z_m.segment(runs[j].first, runs[j].second - runs[j].first);
    span[j] = z.maxCoeff() - z.minCoeff();
  }
  std::vector<double> sorted = span;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double wide = 3.0 * (sorted.empty() ? 0.0 : sorted[sorted.size() / 2]);
  std::vector<std::pair<Eigen::Index, Eigen::Index>> points;
  for (std::size_t j = 0; j < runs.size(); ++j) {
    if (span[j] > wide && span[j] > 0.0) {
      for (Eigen::Index k = runs[j].first; k < runs[j].second; ++k) points.emplace_back(k, k + 1);
    } else {
      points.push_back(runs[j]);
    }
  }
  runs = std::move(points);
  const auto m = static_cast<Eigen::Index>(runs.size());
  for (Eigen::VectorXd* v : {&f.z_m, &f.F_N, &f.w, &f.szz, &f.sff, &f.szf}) v->resize(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const auto [b, e] = runs[static_cast<std::size_t>(j)];
    const auto z = d.z_m.segment(b, e - b).array();
    const auto F = d.F_N.segment(b, e - b).array();
    f.w[j] = static_cast<double>(e - b);
    f.z_m[j] = z.mean();
    f.F_N[j] = F.mean();
    f.szz[j] = (z - f.z_m[j]).square().sum();
    f.sff[j] = (F - f.F_N[j]).square().sum();
    f.szf[j] = ((z - f.z_m[j]) * (F - f.F_N[j])).sum();
  }
  return f;
}

}  // namespace

detail::FitData detail::collect_loading(const Curve& c, const IndentationParams& p) {
  validate(c, p);
  FitData d;
  std::vector<int> idx;
  int rep_ord = 0, below = 0;
  d.max_i_A = c.i_A.size() ? c.i_A.maxCoeff() : 0.0;
  for (auto [begin, end] : detail::repetitions(c)) {
    Curve one;
    one.z_m = c.z_m.segment(begin, end - begin);
    one.i_A = c.i_A.segment(begin, end - begin);
    bool first = true;
    for (int k : loading_branch(one).loading) {
      const int g = begin + k;
      idx.push_back(g);
      d.rep_of.push_back(rep_ord);
      if (c.i_A[g] >= p.contact_current_A) {
        ++d.n_contact;
        if (first) { d.first_contact_z_m.push_back(c.z_m[g]); d.first_contact_rep.push_back(rep_ord); first = false; }
      }
      if (c.i_A[g] < p.contact_current_A - kBaselineMarginA) ++below;
    }
    ++rep_ord;
  }
  d.has_baseline = below >= kBaselineMinSamples;
  d.z_m.resize(static_cast<Eigen::Index>(idx.size()));
  d.F_N.resize(d.z_m.size());
  for (size_t k = 0; k < idx.size(); ++k) {
    d.z_m[static_cast<Eigen::Index>(k)] = c.z_m[idx[k]];
    d.F_N[static_cast<Eigen::Index>(k)] = p.force_constant_at(c.z_m[idx[k]]) * (c.i_A[idx[k]] - p.contact_current_A);
  }
  d.points = fit_points(c, d, idx, p);
  return d;
}

void detail::require_contact(const FitData& d, const IndentationParams& p) {
  if (d.n_contact == 0)
    throw DataError("no contact: no loading sample reaches the contact current I_c = " +
                      detail::number_text(p.contact_current_A) + " A (highest current " + detail::number_text(d.max_i_A) + " A)");
  if (d.n_contact < p.min_points)
    throw DataError("too few points: " + std::to_string(d.n_contact) +
                      " loading samples at or above I_c = " + detail::number_text(p.contact_current_A) +
                      " A, the fits need at least " + std::to_string(p.min_points));
}

Value local_force_N(const Eigen::VectorXd& depth, const Eigen::VectorXd& Fo, double at,
                    double hw) {
  double s0 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, lo = INFINITY, hi = -INFINITY;
  for (Eigen::Index k = 0; k < depth.size(); ++k) {
    if (std::abs(depth[k] - at) > hw) continue;
    const double x = depth[k] - at;
    s0 += 1; sx += x; sy += Fo[k]; sxx += x * x; sxy += x * Fo[k];
    lo = std::min(lo, x); hi = std::max(hi, x);
  }
  const std::string where = " within +-" + detail::number_text(hw * 1e3) + " mm of " + detail::number_text(at * 1e3) + " mm depth";
  if (s0 < 2) {
    const double deepest = depth.size() ? depth.maxCoeff() : -INFINITY;
    if (deepest < at)
      return Value::absent("the loading branch does not reach " + detail::number_text(at * 1e3) +
                           " mm depth (deepest " + detail::number_text(deepest * 1e3) + " mm)");
    return Value::absent("fewer than 2 samples" + where +
                         ": the depth steps are coarser than the window");
  }
  // The local line must be supported over at least half the window, and on both sides of `at`
  // or close to it: a staircase ramp whose steps are coarser than the window gives one level.
  if (!(hi - lo >= hw) || lo > 0.5 * hw || hi < -0.5 * hw)
    return Value::absent("the samples" + where + " span only " + detail::number_text((hi - lo) * 1e6) +
                         " um (from " + detail::number_text(lo * 1e6) + " to " + detail::number_text(hi * 1e6) +
                         " um): the depth steps are coarser than the window");
  const double det = s0 * sxx - sx * sx;
  return Value::of((sxx * sy - sx * sxy) / det);  // the local line's value at `at`
}

Value finite_difference_stiffness(const Eigen::VectorXd& depth, const Eigen::VectorXd& Fo,
                                  const IndentationParams& p) {
  const Value lo = local_force_N(depth, Fo, p.window_lo_m, p.local_half_width_m);
  const Value hi = local_force_N(depth, Fo, p.window_hi_m, p.local_half_width_m);
  if (!lo) return lo;
  if (!hi) return hi;
  return Value::of((*hi.value - *lo.value) / (p.window_hi_m - p.window_lo_m));
}

Value window_slope(const Eigen::VectorXd& depth, const Eigen::VectorXd& Fo,
                   const IndentationParams& p) {
  double s0 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, dmin = INFINITY, dmax = -INFINITY;
  for (Eigen::Index k = 0; k < depth.size(); ++k) {
    if (depth[k] < p.window_lo_m || depth[k] > p.window_hi_m) continue;
    s0 += 1; sx += depth[k]; sy += Fo[k]; sxx += depth[k] * depth[k]; sxy += depth[k] * Fo[k];
    dmin = std::min(dmin, depth[k]); dmax = std::max(dmax, depth[k]);
  }
  if (s0 < 3 || !(dmax - dmin > 0.5 * (p.window_hi_m - p.window_lo_m)))
    return Value::absent("the loading samples do not cover half of the " + detail::number_text(p.window_lo_m * 1e3) +
                         "-" + detail::number_text(p.window_hi_m * 1e3) + " mm depth window");
  return Value::of((s0 * sxy - sx * sy) / (s0 * sxx - sx * sx));
}

IndentationResult analyze_indentation(const Curve& c, const IndentationParams& p) {
  IndentationResult res;
  res.F0_N = p.force_constant_N_per_A * (p.bias_current_A - p.contact_current_A);
  res.tangent_depths_m = p.tangent_depths_m;
  const detail::FitData d = detail::collect_loading(c, p);  // throws on malformed input
  const Branches br = loading_branch(c);
  res.n_loading = static_cast<int>(br.loading.size());
  res.n_unloading = static_cast<int>(br.unloading.size());
  res.has_baseline = d.has_baseline;
  auto all_absent = [&](const std::string& why) {
    res.fit_reason = why;
    for (Value* v : {&res.contact_z_m, &res.delta0_m, &res.k_tangent_at_delta0_N_per_m,
                     &res.k_fd_N_per_m, &res.k_window_N_per_m, &res.k_fd_paper_N_per_m,
                     &res.k_window_paper_N_per_m})
      *v = Value::absent(why);
    res.k_tangent_N_per_m.assign(p.tangent_depths_m.size(), Value::absent(why));
    return res;
  };
  res.fitted_on = d.points.on;
  res.n_fit_points = static_cast<int>(d.points.z_m.size());
  try {
    detail::require_contact(d, p);
  } catch (const DataError& e) {
    if (d.n_contact == 0) return all_absent(e.what());
    throw;  // too few points: the recording is unusable, say so
  }
  // Each model on its own: one that cannot be fitted is absent with its reason.
  auto attempt = [](std::optional<ModelFit>& out, std::string& why, auto&& fit) {
    try {
      out = fit();
    } catch (const DataError& e) {
      why = e.what();
    }
  };
  attempt(res.linear, res.linear_reason, [&] { return detail::fit_model(Model::linear, d, p); });
  attempt(res.hertz, res.hertz_reason, [&] { return detail::fit_model(Model::hertz, d, p); });
  if (res.hertz) {
    attempt(res.sneddon, res.sneddon_reason, [&] { return detail::fit_model(Model::sneddon, d, p, &*res.hertz); });
  } else {
    res.sneddon_reason = "the Sneddon fit starts from the Hertz fit, which failed: " + res.hertz_reason;
  }
  res.contact_estimates = detail::estimate_contact(d, p);
  const ModelFit* best = nullptr;
  for (const auto* m : {&res.linear, &res.hertz, &res.sneddon})
    if (*m && (!best || (*m)->aic < best->aic)) best = &**m;
  if (!best) {
    return all_absent("no model could be fitted: linear: " + res.linear_reason +
                      "; hertz: " + res.hertz_reason);
  }
  res.chosen = best->model;
  res.contact_z_m = Value::of(best->contact_z_m);

  // Model-free descriptors from the fitted contact point.
  const Eigen::VectorXd depth = (d.z_m.array() - best->contact_z_m).matrix();
  const Eigen::VectorXd Fo = d.F_N - p.spring_N_per_m * depth;
  const double max_depth = depth.maxCoeff();
  res.k_fd_N_per_m = finite_difference_stiffness(depth, Fo, p);
  res.k_window_N_per_m = window_slope(depth, Fo, p);

  // The paper's variant: depths from each repetition's first sample at i >= I_c.
  Eigen::VectorXd depth_p(d.z_m.size()), Fo_p(d.z_m.size());
  Eigen::Index np = 0;
  for (Eigen::Index k = 0; k < d.z_m.size(); ++k) {
    const auto it = std::find(d.first_contact_rep.begin(), d.first_contact_rep.end(), d.rep_of[static_cast<size_t>(k)]);
    if (it == d.first_contact_rep.end()) continue;
    const double origin = d.first_contact_z_m[static_cast<size_t>(it - d.first_contact_rep.begin())];
    depth_p[np] = d.z_m[k] - origin;
    Fo_p[np] = d.F_N[k] - p.spring_N_per_m * depth_p[np];
    ++np;
  }
  res.k_fd_paper_N_per_m = finite_difference_stiffness(depth_p.head(np), Fo_p.head(np), p);
  res.k_window_paper_N_per_m = window_slope(depth_p.head(np), Fo_p.head(np), p);

  // Operating point: F_o(delta0) = F_0 on the chosen model (monotone: bisection).
  const std::string beyond = " mm, beyond the deepest loading sample (" + detail::number_text(max_depth * 1e3) + " mm)";
  if (!(res.F0_N > 0.0)) {
    res.delta0_m = Value::absent("bias current I_0 = " + detail::number_text(p.bias_current_A) +
                                 " A gives no positive object force above I_c");
  } else {
    double lo = 0.0, hi = std::max(max_depth, 1e-6);
    while (best->force_N(hi) < res.F0_N && hi < 10.0) hi *= 2.0;
    if (best->force_N(hi) < res.F0_N) {
      res.delta0_m = Value::absent("the fitted model does not reach F_0 = " + detail::number_text(res.F0_N) + " N");
    } else {
      for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
        const double mid = 0.5 * (lo + hi);
        (best->force_N(mid) < res.F0_N ? lo : hi) = mid;
      }
      const double d0 = 0.5 * (lo + hi);
      if (d0 > max_depth) res.delta0_m = Value::absent("delta0 = " + detail::number_text(d0 * 1e3) + beyond);
      else res.delta0_m = Value::of(d0);
    }
  }
  res.k_tangent_at_delta0_N_per_m = res.delta0_m
      ? Value::of(best->stiffness_N_per_m(*res.delta0_m.value)) : Value::absent(res.delta0_m.reason);
  for (double dd : p.tangent_depths_m) {
    if (dd > max_depth) res.k_tangent_N_per_m.push_back(Value::absent("depth " + detail::number_text(dd * 1e3) + beyond));
    else res.k_tangent_N_per_m.push_back(Value::of(best->stiffness_N_per_m(dd)));
  }
  return res;
}

RepetitionStats repetition_mean_sd(const Curve& c, const IndentationParams& p, double contact_z_m,
                                   const Eigen::VectorXd& grid) {
  validate(c, p);
  const Eigen::Index G = grid.size();
  RepetitionStats s{grid, Eigen::VectorXd::Zero(G), Eigen::VectorXd::Zero(G), Eigen::VectorXi::Zero(G)};
  Eigen::VectorXd sum2 = Eigen::VectorXd::Zero(G);
  for (auto [begin, end] : detail::repetitions(c)) {
    Curve one{c.z_m.segment(begin, end - begin), c.i_A.segment(begin, end - begin), {}, {}};
    std::vector<std::pair<double, double>> pts;  // (depth, F_o), sorted by depth
    const Eigen::VectorXd Fo = object_force_N(one, p, contact_z_m);
    for (int k : loading_branch(one).loading) pts.emplace_back(one.z_m[k] - contact_z_m, Fo[k]);
    std::sort(pts.begin(), pts.end());
    if (pts.size() < 2) continue;
    for (Eigen::Index g = 0; g < G; ++g) {
      const double x = grid[g];
      if (x < pts.front().first || x > pts.back().first) continue;
      auto it = std::lower_bound(pts.begin(), pts.end(), std::make_pair(x, -HUGE_VAL));
      if (it == pts.begin()) ++it;
      const auto& a = *(it - 1);
      const auto& b = *it;
      const double f = b.first > a.first ? a.second + (b.second - a.second) * (x - a.first) / (b.first - a.first)
                                         : 0.5 * (a.second + b.second);
      s.mean_N[g] += f;
      sum2[g] += f * f;
      ++s.count[g];
    }
  }
  for (Eigen::Index g = 0; g < G; ++g) {
    const int n = s.count[g];
    if (n == 0) continue;
    const double m = s.mean_N[g] / n;
    s.mean_N[g] = m;
    s.sd_N[g] = n > 1 ? std::sqrt(std::max(0.0, (sum2[g] - n * m * m) / (n - 1))) : 0.0;
  }
  return s;
}

MeanSd mean_sd(const std::vector<Value>& per_rep) {
  MeanSd out;
  double s = 0, s2 = 0;
  for (const Value& v : per_rep) if (v) { s += *v.value; s2 += *v.value * *v.value; ++out.n; }
  if (out.n == 0) { out.mean = out.sd = Value::absent("no repetition has a value"); return out; }
  const double m = s / out.n;
  out.mean = Value::of(m);
  out.sd = out.n > 1 ? Value::of(std::sqrt(std::max(0.0, (s2 - out.n * m * m) / (out.n - 1))))
                     : Value::absent("s.d. needs at least 2 repetitions with a value");
  return out;
}

std::vector<std::pair<int, int>> detail::repetitions(const Curve& c) {
  std::vector<std::pair<int, int>> runs;
  const int n = static_cast<int>(c.z_m.size());
  if (n == 0) return runs;
  if (c.rep.size() == 0) return {{0, n}};
  int b = 0;
  for (int k = 1; k <= n; ++k) {
    if (k == n || c.rep[k] != c.rep[b]) { runs.emplace_back(b, k); b = k; }
  }
  return runs;
}

}  // namespace palp::analysis
