// SPDX-License-Identifier: Apache-2.0
// Shared between the analysis sources (private).
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "palp/analysis/indentation.hpp"

namespace palp::analysis::detail {

/// The points a fit runs on: samples (w = 1, no scatter) or plateau means (w = sample count,
/// with the centred sums of squares of the plateau's samples, for the RSS over every sample).
struct FitPoints {
  Eigen::VectorXd z_m, F_N, w;
  Eigen::VectorXd szz, sff, szf;  ///< sum (z - zbar)^2, (F - Fbar)^2, (z - zbar)(F - Fbar)
  FitOn on = FitOn::samples;
  double n_samples() const { return w.sum(); }
  /// The part of the samples' squared residuals inside the plateaus that no slope removes:
  /// sum of sff - szf^2/szz (the fit's plateau rows carry the rest).
  double scatter_floor() const;
};

/// Loading samples ready for a fit: position and coil force F = K_f (i - I_c).
struct FitData {
  Eigen::VectorXd z_m, F_N;
  FitPoints points;                  ///< what the fits run on (see IndentationParams::fit_on)
  std::vector<int> rep_of;           ///< repetition ordinal (0..) of each loading sample
  std::vector<double> first_contact_z_m;  ///< per repetition: z of the first sample at i >= I_c
                                          ///< (NaN-free: repetitions without one are skipped)
  std::vector<int> first_contact_rep;
  bool has_baseline = false;
  int n_contact = 0;                 ///< loading samples with i >= I_c
  double max_i_A = 0.0;
};

/// Loading samples below I_c - this count as a baseline (2 steps of the paper's ramp, many
/// times the current noise); at least kBaselineMinSamples of them make a baseline.
constexpr double kBaselineMarginA = 0.02;
constexpr int kBaselineMinSamples = 5;

/// Contiguous runs of equal rep values: [begin, end) per repetition (one run without reps).
std::vector<std::pair<int, int>> repetitions(const Curve& c);

/// Validates and collects; does not check for contact (callers decide: throw or reason).
FitData collect_loading(const Curve& c, const IndentationParams& p);
/// Throws DataError when there is no contact or too few contact samples.
void require_contact(const FitData& d, const IndentationParams& p);
/// A model fit of collected data (require_contact passed); start: a fit to begin from (the
/// Sneddon fit from the Hertz one), else the profile over z_c. Throws DataError when no
/// contact point gives a positive stiffness.
ModelFit fit_model(Model model, const FitData& d, const IndentationParams& p,
                   const ModelFit* start = nullptr);
/// estimate_contact on collected data.
std::vector<ContactEstimate> estimate_contact(const FitData& d, const IndentationParams& p);

}  // namespace palp::analysis::detail
