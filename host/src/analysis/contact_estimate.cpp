// SPDX-License-Identifier: Apache-2.0
// Initial contact-point estimates: see estimate_contact in palp/analysis/indentation.hpp.
#include <algorithm>
#include <cmath>
#include <vector>

#include "analysis/indentation_internal.hpp"

namespace palp::analysis {

namespace {

Value median(std::vector<double> v, const char* what) {
  if (v.empty()) return Value::absent(std::string("no repetition gives a ") + what + " estimate");
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return Value::of(n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

struct RepData {
  std::vector<double> z, G;
  int n_base = 0;  // leading samples below I_c - margin
};

std::optional<double> baseline_deviation(const RepData& r) {
  if (r.n_base < detail::kBaselineMinSamples) return std::nullopt;
  double m = 0, m2 = 0;
  for (int k = 0; k < r.n_base; ++k) { m += r.G[k]; m2 += r.G[k] * r.G[k]; }
  m /= r.n_base;
  const double sd = std::sqrt(std::max(0.0, m2 / r.n_base - m * m));
  const double range = *std::max_element(r.G.begin(), r.G.end()) - m;
  const double thr = m + std::max(5.0 * sd, 1e-3 * range);
  const int n = static_cast<int>(r.G.size());
  for (int k = r.n_base; k < n; ++k) {
    bool stays = true;
    for (int j = k; j < std::min(n, k + 5); ++j) stays = stays && r.G[j] > thr;
    if (stays) return r.z[k];
  }
  return std::nullopt;
}

std::optional<double> piecewise_fit(const RepData& r) {
  const double gmin = *std::min_element(r.G.begin(), r.G.end());
  const double gmax = *std::max_element(r.G.begin(), r.G.end());
  int n = 0;
  while (n < static_cast<int>(r.G.size()) && r.G[n] <= gmin + 0.05 * (gmax - gmin)) ++n;
  if (n < 6) return std::nullopt;
  // Suffix sums for the line part, prefix sums for the constant part.
  std::vector<double> S1(n + 1, 0), Sz(n + 1, 0), Szz(n + 1, 0), Sg(n + 1, 0), Sgg(n + 1, 0), Szg(n + 1, 0);
  for (int k = n - 1; k >= 0; --k) {
    S1[k] = S1[k + 1] + 1; Sz[k] = Sz[k + 1] + r.z[k]; Szz[k] = Szz[k + 1] + r.z[k] * r.z[k];
    Sg[k] = Sg[k + 1] + r.G[k]; Sgg[k] = Sgg[k + 1] + r.G[k] * r.G[k]; Szg[k] = Szg[k + 1] + r.z[k] * r.G[k];
  }
  double best = INFINITY, best_z = 0;
  bool found = false;
  for (int b = 3; b <= n - 3; ++b) {
    const double c0 = (Sg[0] - Sg[b]) / b;  // constant part: samples [0, b)
    const double rss_c = (Sgg[0] - Sgg[b]) - b * c0 * c0;
    const double m = S1[b], sz = Sz[b], szz = Szz[b], sg = Sg[b], szg = Szg[b];
    const double det = m * szz - sz * sz;
    if (!(det > 0)) continue;
    const double slope = (m * szg - sz * sg) / det, icpt = (sg - slope * sz) / m;
    const double rss_l = Sgg[b] - 2 * (slope * szg + icpt * sg) + slope * slope * szz +
                         2 * slope * icpt * sz + icpt * icpt * m;
    if (rss_c + rss_l < best && slope > 0) {
      best = rss_c + rss_l;
      best_z = (c0 - icpt) / slope;
      found = true;
    }
  }
  if (!found) return std::nullopt;
  return best_z;
}

std::optional<double> ratio_of_variances(const RepData& r) {
  const int n = static_cast<int>(r.G.size());
  const int h = std::max(5, n / 20);  // w/2
  if (n < 2 * h + 1) return std::nullopt;
  // prefix sums of G - G[0] and its square: each window's variance in O(1)
  std::vector<double> S(n + 1, 0.0), S2(n + 1, 0.0);
  for (int k = 0; k < n; ++k) {
    const double g = r.G[k] - r.G[0];
    S[k + 1] = S[k] + g;
    S2[k + 1] = S2[k] + g * g;
  }
  auto var = [&](int a, int b) {
    const double m = (S[b] - S[a]) / (b - a);
    return std::max((S2[b] - S2[a]) / (b - a) - m * m, 1e-300);
  };
  double best = -1;
  int arg = -1;
  for (int k = h; k + h <= n; ++k) {
    const double q = var(k, k + h) / var(k - h, k);
    if (q > best) { best = q; arg = k; }
  }
  if (arg < 0) return std::nullopt;
  return r.z[arg];
}

}  // namespace

std::vector<ContactEstimate> estimate_contact(const Curve& c, const IndentationParams& p) {
  return detail::estimate_contact(detail::collect_loading(c, p), p);
}

std::vector<ContactEstimate> detail::estimate_contact(const FitData& d, const IndentationParams& p) {
  if (!d.has_baseline)
    return {{"first_sample_at_Ic", median(d.first_contact_z_m, "first_sample_at_Ic")}};
  std::vector<RepData> reps;
  for (Eigen::Index k = 0; k < d.z_m.size(); ++k) {
    const size_t r = static_cast<size_t>(d.rep_of[static_cast<size_t>(k)]);
    if (reps.size() <= r) reps.resize(r + 1);
    RepData& rd = reps[r];
    const double G = d.F_N[k] - p.spring_N_per_m * d.z_m[k];
    if (rd.z.size() == static_cast<size_t>(rd.n_base) &&
        d.F_N[k] < -p.force_constant_N_per_A * detail::kBaselineMarginA)
      ++rd.n_base;
    rd.z.push_back(d.z_m[k]);
    rd.G.push_back(G);
  }
  std::vector<double> dev, pw, rov;
  for (const RepData& r : reps) {
    if (r.G.empty()) continue;
    if (auto v = baseline_deviation(r)) dev.push_back(*v);
    if (auto v = piecewise_fit(r)) pw.push_back(*v);
    if (auto v = ratio_of_variances(r)) rov.push_back(*v);
  }
  return {{"baseline_deviation", median(dev, "baseline_deviation")},
          {"piecewise_fit", median(pw, "piecewise_fit")},
          {"ratio_of_variances", median(rov, "ratio_of_variances")}};
}

}  // namespace palp::analysis
