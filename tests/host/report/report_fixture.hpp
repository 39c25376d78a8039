// SPDX-License-Identifier: Apache-2.0
// The report tests' known map: a synthetic 9 x 9 map (tests/host/unit/synth_map.hpp: every point
// a result directory of a linear specimen, written by write_result and save_map) whose columns
// 2, 5 and 8 are soft, as the paper's pad over its shallow channels (Fig. 6b).
#pragma once

#include <filesystem>

#include "synth_map.hpp"

namespace palp::test {

inline constexpr int kReportGrid = 9;
inline constexpr double kStiffN_per_m = 2.2e3;  ///< away from the channels
inline constexpr double kSoftN_per_m = 1.4e3;   ///< over them: columns 2, 5, 8

/// k of the known map, N/m: kSoftN_per_m in columns 2, 5 and 8, else kStiffN_per_m; rows differ by
/// 1 % each (from -4 % at row 1 to +4 % at row 9), below the analysis' 10 % contrast.
inline double report_map_k_N_per_m(int row, int column) {
  const bool soft = column == 2 || column == 5 || column == 8;
  return (soft ? kSoftN_per_m : kStiffN_per_m) * (1.0 + 0.01 * (row - 5));
}

/// The known map in `dir` (one repetition per point, to keep it quick).
inline StiffnessMap write_report_map(const std::filesystem::path& dir) {
  return write_synth_map(dir, kReportGrid, kReportGrid, 1, report_map_k_N_per_m);
}

}  // namespace palp::test
