// Shared between the analysis sources (private).
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "palp/analysis/indentation.hpp"

namespace palp::analysis::detail {

/// Loading samples ready for a fit: position and coil force F = K_f (i - I_c).
struct FitData {
  Eigen::VectorXd z_m, F_N;
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
/// Throws ConfigError when there is no contact or too few contact samples.
void require_contact(const FitData& d, const IndentationParams& p);
/// The Sneddon fit started from a Hertz fit of the same data (saves refitting Hertz).
ModelFit fit_sneddon_from(const Curve& c, const IndentationParams& p, const ModelFit& hertz);

}  // namespace palp::analysis::detail
