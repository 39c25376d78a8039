// SPDX-License-Identifier: Apache-2.0
// The pressure–force test of a recording (paper §V-D), one definition for palp::indent (its
// run.pressure), `palpctl analyze pressure` and Python's palp.analyze.pressure.
//
//   palp::Recording rec = palp::read_recording("results/pad-r5c2/indentation.csv");
//   palp::analysis::PressureResult pr = palp::pressure_analysis_of(rec, params);
//   nlohmann::json j = palp::pressure_summary_json(pr);   // result.hpp: the --json keys
//
// Every pressure column the recording has (p1_Pa..p6_Pa) is regressed on the object force
// F_o = K_f (i - I_c) - k_v (z - z_c) of the loading samples at i >= I_c (analysis/pressure.hpp),
// z_c the contact point of the indentation analysis of the same recording with the same params
// (analyze_indentation: the chosen model's). A channel keeps its number: a recording with only
// p2_Pa and p5_Pa gives channels 2 and 5.
//
// Errors: DataError when the recording has no pressure column, when the indentation analysis
// gives no contact point (with its reason), or from the analyses (a NaN sample, no loading sample
// at i >= I_c); ConfigError for bad params.
#pragma once

#include "palp/analysis/indentation.hpp"
#include "palp/analysis/pressure.hpp"
#include "palp/recording.hpp"

namespace palp {

/// The pressure–force test of a recording: the indentation analysis for the contact point, then
/// every pressure column against the object force.
analysis::PressureResult pressure_analysis_of(const Recording& recording,
                                              const analysis::IndentationParams& params);

/// The same with the indentation analysis of this recording already done (indent() has it): its
/// contact point is used and nothing is fitted again.
analysis::PressureResult pressure_analysis_of(const Recording& recording,
                                              const analysis::IndentationParams& params,
                                              const analysis::IndentationResult& indentation);

}  // namespace palp
