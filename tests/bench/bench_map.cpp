// SPDX-License-Identifier: Apache-2.0
// The time to analyse indentations of the 2D protocol (issues 6, 16): one point, 3 repetitions
// of the staircase 0.5 -> 3 A by 0.01 A every 25 ms with symmetric unload, sampled at 1 kHz
// (37 500 samples), analysed as palp::analyze_run does it (every repetition alone, then all
// pooled: linear, Hertz and Sneddon fits with the contact point); and a whole 9 x 9 map of such
// points. The fits run on the staircase's plateau means (the default) or on every sample.
// Synthetic curves of a known object: F_o = k delta + 4/3 E* sqrt(R) delta^1.5, softer on
// columns 2, 5, 8; 1 um encoder quantisation and 2 mA rms current noise; the commanded current
// recorded as the device does (it marks the plateaus).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "palp/analysis/indentation.hpp"

namespace {

namespace an = palp::analysis;

an::Curve synthetic_point(double k_N_per_m, double Estar_Pa, std::mt19937_64& rng) {
  const double Kf = 2.918, Ic = 0.5, kv = 43.9, R = 2.5e-3, zc = 24.8e-3;
  std::normal_distribution<double> noise(0.0, 2e-3);
  std::vector<double> z, i, i_cmd;
  std::vector<int> rep;
  for (int r = 0; r < 3; ++r) {
    for (int step = 0; step <= 500; ++step) {
      const int s = step <= 250 ? step : 500 - step;
      const double I = 0.5 + 0.01 * s;
      // K_f (I - I_c) = k_v delta + F_o(delta): Newton from the last depth
      const double target = Kf * (I - Ic);
      double d = std::max(target / (kv + k_N_per_m) * 0.5, 0.0);
      for (int it = 0; it < 30 && target > 0; ++it) {
        const double f = kv * d + k_N_per_m * d + 4.0 / 3.0 * Estar_Pa * std::sqrt(R) * d * std::sqrt(d) - target;
        const double df = kv + k_N_per_m + 2.0 * Estar_Pa * std::sqrt(R * d);
        d = std::max(d - f / df, 0.0);
      }
      for (int k = 0; k < 25; ++k) {
        z.push_back(std::round((zc + d) * 1e6) * 1e-6);
        i.push_back(I + noise(rng));
        i_cmd.push_back(I);
        rep.push_back(r);
      }
    }
  }
  an::Curve c;
  c.z_m = Eigen::Map<Eigen::VectorXd>(z.data(), static_cast<Eigen::Index>(z.size()));
  c.i_A = Eigen::Map<Eigen::VectorXd>(i.data(), static_cast<Eigen::Index>(i.size()));
  c.rep = Eigen::Map<Eigen::VectorXi>(rep.data(), static_cast<Eigen::Index>(rep.size()));
  c.i_cmd_A = Eigen::Map<Eigen::VectorXd>(i_cmd.data(), static_cast<Eigen::Index>(i_cmd.size()));
  return c;
}

an::IndentationParams params_fitting_on(std::int64_t plateaus) {
  an::IndentationParams p{};
  p.fit_on = plateaus != 0 ? an::FitOn::plateaus : an::FitOn::samples;
  return p;
}

// One point as analyze_run analyses it; true when the pooled analysis has k_fd.
bool analyse_point(const an::Curve& c, const an::IndentationParams& p) {
  const an::RepetitionSummary reps = an::analyze_repetitions(c, p);
  const an::IndentationResult pooled = an::analyze_indentation(c, p);
  benchmark::DoNotOptimize(reps);
  return pooled.k_fd_N_per_m.value.has_value();
}

// Arg: 1 = fits on plateaus, 0 = on samples.
void BM_AnalyseOnePoint3Reps(benchmark::State& state) {
  std::mt19937_64 rng(7);
  const an::Curve c = synthetic_point(1200.0, 1.4e6, rng);
  const an::IndentationParams p = params_fitting_on(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(analyse_point(c, p));
  state.counters["samples"] = static_cast<double>(c.z_m.size());
}
BENCHMARK(BM_AnalyseOnePoint3Reps)->ArgName("plateaus")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_AnalyseWholeMap9x9x3(benchmark::State& state) {
  std::mt19937_64 rng(7);
  std::vector<an::Curve> map;
  for (int r = 1; r <= 9; ++r)
    for (int c = 1; c <= 9; ++c) {
      const bool soft = c == 2 || c == 5 || c == 8;
      map.push_back(synthetic_point(soft ? 600.0 : 1200.0, soft ? 0.8e6 : 1.4e6, rng));
    }
  const an::IndentationParams p = params_fitting_on(state.range(0));
  std::size_t samples = 0;
  for (const auto& c : map) samples += static_cast<std::size_t>(c.z_m.size());
  for (auto _ : state) {
    int with_k = 0;
    for (const an::Curve& c : map) with_k += analyse_point(c, p) ? 1 : 0;
    state.counters["points_with_k_fd"] = with_k;
  }
  state.counters["samples"] = static_cast<double>(samples);
  state.counters["points"] = static_cast<double>(map.size());
}
// the samples path takes ~25 s for the map (its single point above shows the ratio)
BENCHMARK(BM_AnalyseWholeMap9x9x3)->ArgName("plateaus")->Arg(1)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
