// Built against an installed palp with palp::analysis alone: a Hertz force with a known value and
// the repetitions of a synthetic two-ramp current trace, both from the installed library.
#include <cstdio>
#include <vector>

#include "palp/analysis/contact_models.hpp"
#include "palp/recording_types.hpp"

int main() {
  // 4/3 E* sqrt(R) d^1.5 with E* = 100 kPa, R = 2.5 mm, d = 1 mm: 0.210819 N
  std::printf("hertz_N %.6f\n", palp::analysis::hertz_force_N(1e-3, 1e5, 2.5e-3));
  std::vector<double> i_A;
  for (int rep = 0; rep < 2; ++rep) {
    for (int k = 0; k <= 250; ++k) i_A.push_back(0.5 + 0.01 * k);
    for (int k = 249; k >= 0; --k) i_A.push_back(0.5 + 0.01 * k);
  }
  const std::vector<int> rep = palp::split_repetitions_at_current_minima(i_A);
  std::printf("repetitions %d\n", rep.back() + 1);
  return 0;
}
