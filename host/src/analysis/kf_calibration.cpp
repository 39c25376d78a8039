// SPDX-License-Identifier: Apache-2.0
// Force-constant calibration in free air (kf_calibration.hpp): static points cut from the
// staircase with the ramp's exact schedule, and the linear least-squares fit of the absolute
// balance K_f(s) i - c = k_v s with K_f piecewise linear over nodes.
#include "palp/analysis/kf_calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "frf_internal.hpp"
#include "palp/error.hpp"
#include "palp/protocol/program_schedule.hpp"

namespace palp::analysis {
namespace {

using detail::strf;

/// Commanded current of ramp level j (the direction toward stop_A).
double level_current_A(const proto::LoadRamp& m, std::uint32_t j) {
  const double step = m.stop_A < m.start_A ? -static_cast<double>(m.step_A) : m.step_A;
  return m.start_A + step * j;
}

/// The ramp's first tick (absolute) as an interval [lo, hi]: every climb from level j - 1 to j
/// of the first repetition falls between two samples, at start + j dwell ticks.
struct StartInterval {
  std::int64_t lo = 0, hi = 0;
};
StartInterval ramp_start(const detail::TickedRecording& r, const proto::LoadRamp& m,
                         const proto::RampTiming& t, const char* who) {
  const std::vector<double>& c = *r.rec->i_cmd_A;
  const double step = std::abs(static_cast<double>(m.step_A));
  StartInterval s{std::numeric_limits<std::int64_t>::min(),
                  std::numeric_limits<std::int64_t>::max()};
  std::size_t k = 1;
  for (std::uint32_t j = 1; j < t.levels; ++j) {
    const double target = level_current_A(m, j);
    // the first sample at level j (within half a step) after one at level j - 1
    while (k < c.size() && !(std::abs(c[k] - target) < 0.5 * step &&
                             std::abs(c[k - 1] - level_current_A(m, j - 1)) < 0.5 * step))
      ++k;
    if (k == c.size()) {
      if (j == 1)
        throw ConfigError(strf("%s: the commanded current (i_cmd_A) never steps from the ramp's "
                               "first level (%.4f A) to its second",
                               who, level_current_A(m, 0)));
      break;  // the first repetition is cut short: the coverage check names it
    }
    const std::int64_t climb = static_cast<std::int64_t>(j) * t.dwell_ticks;
    s.lo = std::max(s.lo, r.tick[k - 1] + 1 - climb);
    s.hi = std::min(s.hi, r.tick[k] - climb);
    ++k;
  }
  if (s.lo > s.hi)
    throw ConfigError(strf("%s: the commanded current does not climb on the ramp's schedule "
                           "(dwell %u ticks at %u Hz)",
                           who, t.dwell_ticks, r.rate_Hz));
  return s;
}

double sd_at(const std::vector<double>& v, const std::vector<std::size_t>& idx, double mean) {
  if (idx.size() < 2) return 0.0;
  double s = 0;
  for (std::size_t k : idx) s += (v[k] - mean) * (v[k] - mean);
  return std::sqrt(s / static_cast<double>(idx.size() - 1));
}

/// Hat function j of the nodes at s (constant beyond the ends).
double hat(std::span<const double> nodes, std::size_t j, double s) {
  const std::size_t n = nodes.size();
  if (s <= nodes.front()) return j == 0 ? 1.0 : 0.0;
  if (s >= nodes.back()) return j == n - 1 ? 1.0 : 0.0;
  if (j > 0 && s >= nodes[j - 1] && s <= nodes[j])
    return (s - nodes[j - 1]) / (nodes[j] - nodes[j - 1]);
  if (j + 1 < n && s >= nodes[j] && s <= nodes[j + 1])
    return (nodes[j + 1] - s) / (nodes[j + 1] - nodes[j]);
  return 0.0;
}

}  // namespace

std::vector<KfStaticPoint> kf_static_points(const Recording& rec, const proto::LoadRamp& ramp,
                                            std::uint32_t control_rate_Hz,
                                            double stroke_origin_z_m, double settled_fraction) {
  const char* who = "kf_static_points";
  const detail::TickedRecording r = detail::ticked(rec, control_rate_Hz, who);
  if (!(settled_fraction > 0 && settled_fraction <= 1))
    throw ConfigError(strf("%s: settled_fraction must be in (0, 1] (got %g)", who,
                           settled_fraction));
  if (ramp.displacement_limit_counts != 0)
    throw ConfigError(strf("%s: a ramp with a displacement limit turns where the coil went, not "
                           "on its schedule: calibrate with displacement_limit_counts 0",
                           who));
  const proto::RampTiming t = proto::ramp_timing(ramp, control_rate_Hz);
  if (t.levels < 2)
    throw ConfigError(strf("%s: the ramp has one level: nothing to calibrate", who));
  const StartInterval s = ramp_start(r, ramp, t, who);
  const double rate = control_rate_Hz;
  const auto total = static_cast<std::int64_t>(t.total_ticks);
  if (r.tick.back() < s.lo + total - r.interval_ticks)
    throw ConfigError(strf("%s: the recording ends at %.6f s, before the ramp does (%.6f s; it "
                           "started at %.6f s)",
                           who, rec.t_s.back(), static_cast<double>(s.lo + total) / rate,
                           static_cast<double>(s.lo) / rate));

  // the settled part of every stair, safe for any start in [lo, hi]
  const auto dwell = static_cast<std::int64_t>(t.dwell_ticks);
  const auto settle = static_cast<std::int64_t>(std::ceil((1.0 - settled_fraction) * dwell));
  std::vector<KfStaticPoint> points;
  const std::uint64_t stairs = static_cast<std::uint64_t>(t.stairs_per_rep) * ramp.repetitions;
  for (std::uint64_t q = 0; q < stairs; ++q) {
    const auto begin = static_cast<std::int64_t>(q) * dwell;
    const auto lo = std::lower_bound(r.tick.begin(), r.tick.end(), s.hi + begin + settle);
    const auto hi = std::lower_bound(lo, r.tick.end(), s.lo + begin + dwell);
    std::vector<std::size_t> idx;
    for (auto it = lo; it != hi; ++it) idx.push_back(static_cast<std::size_t>(it - r.tick.begin()));
    if (idx.size() < 3)
      throw ConfigError(strf("%s: stair %llu (level %u) has %zu samples in its settled part "
                             "(need 3): a faster stream, a longer dwell or a larger "
                             "settled_fraction",
                             who, static_cast<unsigned long long>(q),
                             proto::ramp_level_at(t, static_cast<std::uint64_t>(begin)),
                             idx.size()));
    KfStaticPoint p;
    p.samples = idx.size();
    const double z_mm = detail::mean_at(rec.z_mm, idx);
    p.stroke_m = z_mm * 1e-3 - stroke_origin_z_m;
    p.stroke_sd_m = sd_at(rec.z_mm, idx, z_mm) * 1e-3;
    p.i_A = detail::mean_at(rec.i_A, idx);
    p.i_sd_A = sd_at(rec.i_A, idx, p.i_A);
    points.push_back(p);
  }
  return points;
}

std::vector<double> kf_nodes_for(std::span<const KfStaticPoint> points, std::size_t max_nodes) {
  if (points.size() < 4)
    throw ConfigError(strf("kf_nodes_for: %zu points (need at least 4)", points.size()));
  if (max_nodes < 2) throw ConfigError("kf_nodes_for: max_nodes must be 2 or more");
  double lo = points.front().stroke_m, hi = lo;
  for (const KfStaticPoint& p : points) {
    lo = std::min(lo, p.stroke_m);
    hi = std::max(hi, p.stroke_m);
  }
  if (!(hi > lo)) throw ConfigError("kf_nodes_for: the points span no stroke");
  // at most points - 3 nodes: fit_kf_table needs two points more than its unknowns
  for (std::size_t n = std::min(max_nodes, points.size() - 3); n >= 2; --n) {
    std::vector<double> nodes(n);
    for (std::size_t j = 0; j < n; ++j)
      nodes[j] = j + 1 == n ? hi : lo + (hi - lo) * static_cast<double>(j) / (n - 1);
    bool enough = true;
    for (std::size_t j = 0; j + 1 < n && enough; ++j) {  // [node_j, node_j+1), the last closed
      const bool last = j + 2 == n;
      const auto between = std::count_if(points.begin(), points.end(), [&](const auto& p) {
        return p.stroke_m >= nodes[j] && (p.stroke_m < nodes[j + 1] || (last && p.stroke_m == hi));
      });
      enough = between >= 2;
    }
    if (enough) return nodes;
  }
  return {lo, hi};  // not reached: two nodes hold every point between them
}

namespace {

/// The fit; with an anchor, as a constraint (one node eliminated).
KfCalibration fit(std::span<const KfStaticPoint> points, double k_v_N_per_m,
                  std::span<const double> node_stroke_m, const KfAnchor* anchor) {
  const char* who = "fit_kf_table";
  if (!(k_v_N_per_m > 0) || !std::isfinite(k_v_N_per_m))
    throw ConfigError(strf("%s: k_v must be > 0 (got %g N/m)", who, k_v_N_per_m));
  const std::size_t n = node_stroke_m.size();
  if (n == 0) throw ConfigError(strf("%s: no nodes", who));
  for (std::size_t j = 0; j < n; ++j)
    if (!std::isfinite(node_stroke_m[j]) || (j > 0 && !(node_stroke_m[j] > node_stroke_m[j - 1])))
      throw ConfigError(strf("%s: the nodes must increase (node %zu)", who, j));
  if (anchor && !(std::isfinite(anchor->stroke_m) && std::isfinite(anchor->kf_N_per_A) &&
                  anchor->kf_N_per_A > 0))
    throw ConfigError(strf("%s: the anchor needs a finite stroke and a finite K_f > 0", who));
  const std::size_t unknowns = n + 1;
  if (points.size() < unknowns + 2)
    throw ConfigError(strf("%s: %zu points for %zu unknowns (need at least %zu)", who,
                           points.size(), unknowns, unknowns + 2));
  for (std::size_t j = 0; j < n; ++j) {
    const double a = j > 0 ? node_stroke_m[j - 1] : -std::numeric_limits<double>::infinity();
    const double b = j + 1 < n ? node_stroke_m[j + 1] : std::numeric_limits<double>::infinity();
    const bool seen = std::any_of(points.begin(), points.end(), [&](const KfStaticPoint& p) {
      return p.stroke_m > a && p.stroke_m < b;
    });
    if (!seen)
      throw ConfigError(strf("%s: no point between the neighbours of the node at %.3f mm: its "
                             "K_f cannot be identified",
                             who, node_stroke_m[j] * 1e3));
  }

  // rows: sum_j hat_j(s) i K_j - c = k_v s (N), unknowns x = (K_0 ... K_n-1, c)
  const auto m = static_cast<Eigen::Index>(points.size());
  const auto u = static_cast<Eigen::Index>(unknowns);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m, u);
  Eigen::VectorXd y(m);
  double i_min = std::numeric_limits<double>::infinity();
  for (Eigen::Index r = 0; r < m; ++r) {
    const KfStaticPoint& p = points[static_cast<std::size_t>(r)];
    for (std::size_t j = 0; j < n; ++j)
      A(r, static_cast<Eigen::Index>(j)) = hat(node_stroke_m, j, p.stroke_m) * p.i_A;
    A(r, u - 1) = -1.0;
    y[r] = k_v_N_per_m * p.stroke_m;
    i_min = std::min(i_min, std::abs(p.i_A));
  }
  // x = T z + x0: without an anchor T = 1; with one, the anchor's node with the largest weight
  // is eliminated, K_a = sum_j hat_j(s_a) K_j solved for it
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(u, u);
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(u);
  if (anchor) {
    Eigen::VectorXd h(u);
    h.setZero();
    for (std::size_t j = 0; j < n; ++j)
      h[static_cast<Eigen::Index>(j)] = hat(node_stroke_m, j, anchor->stroke_m);
    Eigen::Index e = 0;
    h.maxCoeff(&e);
    Eigen::MatrixXd Te = Eigen::MatrixXd::Zero(u, u - 1);
    for (Eigen::Index k = 0, col = 0; k < u; ++k) {
      if (k == e) continue;
      Te(k, col) = 1.0;
      Te(e, col) = -h[k] / h[e];
      ++col;
    }
    T = Te;
    x0[e] = anchor->kf_N_per_A / h[e];
  }
  const Eigen::MatrixXd Az = A * T;
  const Eigen::VectorXd yz = y - A * x0;
  const auto qr = Az.colPivHouseholderQr();
  if (qr.rank() < Az.cols())
    throw ConfigError(strf("%s: the points do not determine the table (rank %lld of %lld)", who,
                           static_cast<long long>(qr.rank()), static_cast<long long>(Az.cols())));
  const Eigen::VectorXd z = qr.solve(yz);
  const Eigen::VectorXd x = T * z + x0;
  const double rss = (Az * z - yz).squaredNorm();
  const auto dof = static_cast<double>(m - Az.cols());
  const Eigen::MatrixXd cov = T * (Az.transpose() * Az).inverse() * T.transpose() * (rss / dof);

  KfCalibration c;
  c.node_stroke_m.assign(node_stroke_m.begin(), node_stroke_m.end());
  double kf_mean = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const auto e = static_cast<Eigen::Index>(j);
    c.kf_N_per_A.push_back(x[e]);
    c.kf_se_N_per_A.push_back(std::sqrt(std::max(0.0, cov(e, e))));
    kf_mean += std::abs(x[e]) / static_cast<double>(n);
  }
  const auto ce = static_cast<Eigen::Index>(n);
  c.c_N = x[ce];
  c.c_se_N = std::sqrt(std::max(0.0, cov(ce, ce)));
  c.k_v_N_per_m = k_v_N_per_m;
  c.residual_rms_N = std::sqrt(rss / static_cast<double>(m));
  c.points = points.size();
  // c's uncertainty moves K_f by dc / i: say so when that exceeds 1 % at the lowest current
  const double moved = c.c_se_N / std::max(i_min, 1e-9);
  if (moved > 0.01 * kf_mean)
    c.warning = strf("K_f is poorly determined: the constant c has a standard error of %.3g N, "
                     "which moves K_f by %.1f %% at the lowest current (%.3f A); free-air points "
                     "fix K_f only up to dc / i: anchor K_f at one position or fit fewer nodes",
                     c.c_se_N, 100 * moved / kf_mean, i_min);
  return c;
}

}  // namespace

KfCalibration fit_kf_table(std::span<const KfStaticPoint> points, double k_v_N_per_m,
                           std::span<const double> node_stroke_m) {
  return fit(points, k_v_N_per_m, node_stroke_m, nullptr);
}

KfCalibration fit_kf_table(std::span<const KfStaticPoint> points, double k_v_N_per_m,
                           std::span<const double> node_stroke_m, const KfAnchor& anchor) {
  return fit(points, k_v_N_per_m, node_stroke_m, &anchor);
}

}  // namespace palp::analysis
