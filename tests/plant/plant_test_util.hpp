// SPDX-License-Identifier: Apache-2.0
// Helpers for the plant tests: a current loop like the firmware's, a quasi-static staircase,
// ring-down analysis and the paper's plain least-squares fits.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "palp/plant/plant.hpp"

namespace palp::plant::test {

inline constexpr double kR = 2.5e-3;  ///< the tip's radius, m (§II-A)

/// The paper's constants for analysis (§IV-A): K_f = 2.918 N/A, I_c = 0.5 A, k_v = 43.9 N/m.
inline constexpr double kKf = 2.918;
inline constexpr double kIc = 0.5;
inline constexpr double kKv = 43.9;
inline constexpr double kF0 = 1.459;  // (1.0 - 0.5) A x 2.918 N/A

/// PI current loop on the sensed current (what the firmware core does), ~1 kHz bandwidth,
/// conditional-integration anti-windup against the supply.
class CurrentLoop {
 public:
  explicit CurrentLoop(const PlantConfig& c)
      : kp_(c.coil.inductance_H * kOmega),
        ki_(c.coil.resistance_ohm * kOmega),
        supply_(c.coil.supply_V),
        r_(c.coil.resistance_ohm) {}

  /// Start the integrator at the voltage that holds current i at rest.
  void prime(double current_A) { integral_ = r_ * current_A; }

  double update(double ref_A, double measured_A, double dt_s) {
    const double e = ref_A - measured_A;
    const double v = kp_ * e + integral_ + ki_ * e * dt_s;
    const double sat = std::clamp(v, -supply_, supply_);
    if (sat == v) integral_ += ki_ * e * dt_s;
    return sat;
  }

 private:
  static constexpr double kOmega = 2.0 * std::numbers::pi * 1000.0;
  double kp_, ki_, supply_, r_;
  double integral_ = 0.0;
};

/// Plant + current loop driven at the configured tick.
struct Rig {
  explicit Rig(PlantConfig c, std::shared_ptr<const Phantom> ph = nullptr)
      : plant(c, std::move(ph)), loop(plant.config()) {}

  /// Put the coil at rest at s with current i (and prime the loop to hold it).
  void start_at(double s_m, double i_A, double v_m_per_s = 0.0) {
    plant.reset_state({s_m, v_m_per_s, i_A});
    loop.prime(i_A);
  }

  /// One tick with current reference i_ref.
  void tick(double i_ref) {
    const double dt = plant.config().tick_period_s;
    plant.step(dt, loop.update(i_ref, plant.current_sense_A(), dt));
  }

  /// Run for `seconds` at i_ref; f(plant) after every tick.
  template <class F>
  void run(double i_ref, double seconds, F&& f) {
    const auto n = static_cast<long>(std::llround(seconds / plant.config().tick_period_s));
    for (long k = 0; k < n; ++k) {
      tick(i_ref);
      f(plant);
    }
  }
  void run(double i_ref, double seconds) {
    run(i_ref, seconds, [](const Plant&) {});
  }

  Plant plant;
  CurrentLoop loop;
};

/// Place the mount so that the tip at the float position just touches the surface at (x, y)
/// (the sphere's first touch: on a slope it is above z_s under the apex).
inline void touch_at_float(Rig& rig, double x_m, double y_m) {
  const double zs =
      sphere_touch(*rig.plant.phantom(), x_m, y_m, rig.plant.config().mechanics.tip_radius_m)
          .apex_z_m;
  rig.plant.set_mount(x_m, y_m, zs - rig.plant.config().mechanics.float_position_m);
  rig.start_at(rig.plant.config().mechanics.float_position_m, kIc);
}

/// One settled step of a staircase: commanded current, encoder depth, paper object force.
struct StairPoint {
  double current_A;
  double depth_m;
  double force_N;  // F_o = K_f (i - I_c) - k_v dz
};

/// Staircase from i0 by di every step_s (mean encoder depth over the last `average_s` of each
/// step; the whole step is the unbiased choice when the contact rings), until i_max or a mean
/// depth beyond depth_max (that step is dropped).
inline std::vector<StairPoint> staircase(Rig& rig, double i0, double di, double step_s,
                                         double i_max, double depth_max, double average_s) {
  std::vector<StairPoint> out;
  const std::int32_t count0 = rig.plant.encoder_count();
  const double res = rig.plant.config().sensors.encoder_resolution_m;
  const double dt = rig.plant.config().tick_period_s;
  const auto n_step = std::llround(step_s / dt);
  const auto n_avg = std::llround(average_s / dt);
  for (int k = 1;; ++k) {
    const double i = i0 + di * k;
    if (i > i_max + 1e-9) break;
    double sum = 0.0;
    for (long long t = 0; t < n_step; ++t) {
      rig.tick(i);
      if (t >= n_step - n_avg) sum += (rig.plant.encoder_count() - count0) * res;
    }
    const double depth = sum / static_cast<double>(n_avg);
    if (depth > depth_max) break;
    out.push_back({i, depth, kKf * (i - kIc) - kKv * depth});
  }
  return out;
}

struct FitResult {
  double delta0_m;     // depth at F_0
  double k_o_N_per_m;  // tangent stiffness at delta0
  double r2;
};

inline double r_squared(const std::vector<StairPoint>& pts, double (*model)(double, double),
                        double p) {
  double mean = 0.0;
  for (const auto& q : pts) mean += q.force_N;
  mean /= static_cast<double>(pts.size());
  double ss_res = 0.0, ss_tot = 0.0;
  for (const auto& q : pts) {
    ss_res += std::pow(q.force_N - model(q.depth_m, p), 2);
    ss_tot += std::pow(q.force_N - mean, 2);
  }
  return 1.0 - ss_res / ss_tot;
}

/// Hertz F = A delta^1.5 (A = 4/3 E* sqrt(R)), plain least squares through the contact point.
inline FitResult fit_hertz(const std::vector<StairPoint>& pts) {
  double num = 0.0, den = 0.0;
  for (const auto& q : pts) {
    if (q.depth_m <= 0.0) continue;
    num += q.force_N * std::pow(q.depth_m, 1.5);
    den += std::pow(q.depth_m, 3.0);
  }
  const double a = num / den;
  const double d0 = std::pow(kF0 / a, 2.0 / 3.0);
  auto model = [](double d, double aa) { return d > 0.0 ? aa * std::pow(d, 1.5) : 0.0; };
  return {d0, 1.5 * a * std::sqrt(d0), r_squared(pts, model, a)};
}

/// Linear F = k delta, plain least squares through the contact point.
inline FitResult fit_linear(const std::vector<StairPoint>& pts) {
  double num = 0.0, den = 0.0;
  for (const auto& q : pts) {
    num += q.force_N * q.depth_m;
    den += q.depth_m * q.depth_m;
  }
  const double k = num / den;
  auto model = [](double d, double kk) { return kk * d; };
  return {kF0 / k, k, r_squared(pts, model, k)};
}

/// Straight line y = a + b x by least squares, with R^2.
struct LineFit {
  double intercept, slope, r2;
};
inline LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sx += x[k];
    sy += y[k];
    sxx += x[k] * x[k];
    sxy += x[k] * y[k];
  }
  const double b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double a = (sy - b * sx) / n;
  double ss_res = 0, ss_tot = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    ss_res += std::pow(y[k] - a - b * x[k], 2);
    ss_tot += std::pow(y[k] - sy / n, 2);
  }
  return {a, b, 1.0 - ss_res / ss_tot};
}

/// Damped frequency and damping ratio of a decaying oscillation x(t) about x_eq: omega_d from
/// the mean spacing of zero crossings, zeta from the mean log decrement of successive
/// half-cycle extremes (Lambda = ln|x_k / x_k+1| = pi zeta / sqrt(1 - zeta^2)).
struct RingDown {
  double omega_d_rad_per_s = 0.0;
  double zeta = 0.0;
  int crossings = 0;
};
inline RingDown analyse_ring_down(const std::vector<double>& t, const std::vector<double>& x,
                                  double x_eq, int max_half_cycles) {
  std::vector<double> zc;
  std::vector<double> peaks;
  double extreme = 0.0;
  for (std::size_t k = 1; k < x.size(); ++k) {
    const double a = x[k - 1] - x_eq, b = x[k] - x_eq;
    if (std::abs(b) > std::abs(extreme)) extreme = b;
    if ((a < 0.0) != (b < 0.0) && a != b) {
      zc.push_back(t[k - 1] + (t[k] - t[k - 1]) * (a / (a - b)));
      peaks.push_back(std::abs(extreme));
      extreme = 0.0;
      if (static_cast<int>(zc.size()) > max_half_cycles) break;
    }
  }
  RingDown r;
  r.crossings = static_cast<int>(zc.size());
  if (zc.size() < 3) return r;
  const double half = (zc.back() - zc.front()) / static_cast<double>(zc.size() - 1);
  r.omega_d_rad_per_s = std::numbers::pi / half;
  double lambda = 0.0;
  int n = 0;
  for (std::size_t k = 1; k + 1 < peaks.size(); ++k) {  // peaks[0] is the release, skip it
    lambda += std::log(peaks[k] / peaks[k + 1]);
    ++n;
  }
  lambda /= n;
  r.zeta = lambda / std::sqrt(std::numbers::pi * std::numbers::pi + lambda * lambda);
  return r;
}

}  // namespace palp::plant::test
