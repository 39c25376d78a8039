// SPDX-License-Identifier: Apache-2.0
// Repetitions of a recording without a rep column: split at the current's minima, with a
// Schmitt trigger so noise cannot split (the rule is documented in recording_types.hpp).
#include <algorithm>
#include <cmath>

#include "palp/recording_types.hpp"

namespace palp {
namespace {

/// The q-quantile (0..1) of values, by selection on a copy (nearest rank).
double quantile(std::span<const double> values, double q) {
  std::vector<double> v(values.begin(), values.end());
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

/// The noise's standard deviation from neighbouring samples: for white noise σ,
/// |x[k+1] − x[k]| has median 0.6745·√2·σ; ramps' steps are too rare to move the median.
double noise_sigma(std::span<const double> x) {
  std::vector<double> d(x.size() - 1);
  for (std::size_t k = 0; k + 1 < x.size(); ++k) d[k] = std::abs(x[k + 1] - x[k]);
  const std::size_t mid = d.size() / 2;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(mid), d.end());
  return d[mid] / (0.6745 * std::sqrt(2.0));
}

/// Where the next repetition starts inside the low stretch [a, b): the middle of its bottom.
std::size_t boundary(std::span<const double> x, std::size_t a, std::size_t b, double tol) {
  const double m = *std::min_element(x.begin() + static_cast<std::ptrdiff_t>(a),
                                     x.begin() + static_cast<std::ptrdiff_t>(b));
  std::size_t first = b, last = a;
  for (std::size_t k = a; k < b; ++k)
    if (x[k] <= m + tol) {
      first = std::min(first, k);
      last = k;
    }
  return first + (last - first + 1) / 2;
}

}  // namespace

std::vector<int> split_repetitions_at_current_minima(std::span<const double> i_A) {
  std::vector<int> rep(i_A.size(), 0);
  if (i_A.size() < 3) return rep;
  const double lo = quantile(i_A, 0.01);
  const double hi = quantile(i_A, 0.99);
  const double range = hi - lo;
  const double sigma = noise_sigma(i_A);
  if (!(range > 20.0 * sigma) || !(range > 0.0)) return rep;  // a hold, not a ramp
  const double up_level = lo + range / 2;
  const double down_level = lo + range / 4;
  const double tol = std::max(range / 50, 4.0 * sigma);

  std::vector<std::size_t> starts;  // first sample of repetitions 1, 2, ...
  bool up = false, been_up = false;
  std::size_t down_from = 0;
  for (std::size_t k = 0; k < i_A.size(); ++k) {
    if (!up && i_A[k] >= up_level) {
      if (been_up) starts.push_back(boundary(i_A, down_from, k, tol));
      up = been_up = true;
    } else if (up && i_A[k] <= down_level) {
      up = false;
      down_from = k;
    }
  }
  int r = 0;
  std::size_t next = 0;
  for (std::size_t k = 0; k < rep.size(); ++k) {
    while (next < starts.size() && k >= starts[next]) {
      ++r;
      ++next;
    }
    rep[k] = r;
  }
  return rep;
}

}  // namespace palp
