// SPDX-License-Identifier: Apache-2.0
// The pressure–force test of a recording (pressure_analysis.hpp).
#include "palp/pressure_analysis.hpp"

#include <cstddef>
#include <vector>

#include "palp/error.hpp"
#include "palp/indent.hpp"

namespace palp {

analysis::PressureResult pressure_analysis_of(const Recording& recording,
                                              const analysis::IndentationParams& params,
                                              const analysis::IndentationResult& indentation) {
  std::vector<std::size_t> present;  // the recorded channels, 0-based
  for (std::size_t ch = 0; ch < recording.p_Pa.size(); ++ch)
    if (recording.p_Pa[ch]) present.push_back(ch);
  if (present.empty()) throw DataError("the recording has no pressure column (p1_Pa .. p6_Pa)");
  if (!indentation.contact_z_m)
    throw DataError("no contact point for the object force: " + indentation.contact_z_m.reason);
  const auto n = static_cast<Eigen::Index>(recording.size());
  Eigen::MatrixXd P(n, static_cast<Eigen::Index>(present.size()));
  for (std::size_t c = 0; c < present.size(); ++c)
    P.col(static_cast<Eigen::Index>(c)) =
        Eigen::Map<const Eigen::VectorXd>(recording.p_Pa[present[c]]->data(), n);
  analysis::PressureResult r =
      analysis::analyze_pressure(curve_of(recording), P, params, *indentation.contact_z_m.value);
  // analyze_pressure numbers the matrix's columns; here they are the recording's channels
  for (std::size_t c = 0; c < r.channels.size(); ++c)
    r.channels[c].channel = static_cast<int>(present[c]) + 1;
  return r;
}

analysis::PressureResult pressure_analysis_of(const Recording& recording,
                                              const analysis::IndentationParams& params) {
  return pressure_analysis_of(recording, params,
                              analysis::analyze_indentation(curve_of(recording), params));
}

}  // namespace palp
