// SPDX-License-Identifier: Apache-2.0
// Built against an installed palp with palp::analysis and palp::recording alone: a Hertz force
// with a known value, the repetitions of a synthetic two-ramp current trace, and that trace
// written as a recording (argv[1]: its stem) and read back from the files, all through the
// installed libraries.
#include <cstdio>
#include <vector>

#include "palp/analysis/contact_models.hpp"
#include "palp/recording.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: analysis_consumer <recording stem>\n");
    return 2;
  }
  // 4/3 E* sqrt(R) d^1.5 with E* = 100 kPa, R = 2.5 mm, d = 1 mm: 0.210819 N
  std::printf("hertz_N %.6f\n", palp::analysis::hertz_force_N(1e-3, 1e5, 2.5e-3));
  std::vector<double> i_A;
  for (int rep = 0; rep < 2; ++rep) {
    for (int k = 0; k <= 250; ++k) i_A.push_back(0.5 + 0.01 * k);
    for (int k = 249; k >= 0; --k) i_A.push_back(0.5 + 0.01 * k);
  }
  const std::vector<int> rep = palp::split_repetitions_at_current_minima(i_A);
  std::printf("repetitions %d\n", rep.back() + 1);

  palp::RecordingWriter writer(argv[1]);
  for (std::size_t k = 0; k < i_A.size(); ++k)
    writer.append({.sample_index = k, .t_s = 1e-3 * static_cast<double>(k), .i_A = i_A[k],
                   .z_mm = 0.1 * i_A[k], .rep = rep[k]});
  writer.finish(palp::Sidecar{});
  const palp::Recording back = palp::read_recording(writer.csv_path());
  std::printf("recording rows %zu i_A[250] %.2f last rep %d same %d\n", back.size(), back.i_A[250],
              back.rep.back(), back.i_A == i_A && back.rep == rep ? 1 : 0);
  return 0;
}
