// SPDX-License-Identifier: Apache-2.0
// Quasi-static indentation analysis (issue 6): plain functions over Eigen data, no I/O, no device.
//
// SI everywhere (m, N, N/m, Pa, A); the CLI converts to lab units. Conventions from DESIGN.md:
// +z points into the specimen, depth delta = z - z_c below the *fitted* contact point z_c.
//
//   F   = K_f (i - I_c)                 coil force above the contact threshold current
//   F_o = F - k_v (z - z_c)             object force (the return springs subtracted)
//
// The fits model the measured F as k_v (z - z_c) + M(max(z - z_c, 0)) [+ c], so z_c is a fit
// parameter of every model (the spring term depends on it too) and the contact point is reported
// with its standard error. Models M (analysis-notes.md, "Quasi-static curves"):
//   linear  k delta (no offset: z_c is where it extrapolates to zero force), Hertz sphere,
//   exact Sneddon sphere, each optionally times the finite-thickness factor; E* and E (nu given).
// Below z_c the probe is in air (F = k_v (z - z_c), F_o = 0). A force offset c is fitted for
// Hertz/Sneddon only when the recording has a baseline; here a baseline means at least 5
// loading samples below I_c - 0.02 A (the ramp began before contact): the paper's protocol
// starts its ramp at I_c already in contact, and then z_c and c are not separable.
// The fits pool the loading branches of all repetitions (one z_c: the arm holds its pose);
// start: a grid profile over z_c (closed-form stiffness per candidate), then a bounded
// Levenberg-Marquardt with an analytic Jacobian; no state carried between calls.
// Model choice: lowest AIC = n ln(RSS/n) + 2p. Standard errors: Cov = (J^T J)^-1 RSS/(n - p).
// What the fits run on (IndentationParams::fit_on): the staircase's plateaus (default) or every
// loading sample. A plateau is a run of loading samples of one repetition at one commanded
// current (Curve::i_cmd_A, the ramp program as the device ran it); the fit uses its mean z and
// mean F weighted by its sample count (its mean's variance is sigma^2/n_j under the samples
// fit's equal-noise assumption), plus one residual per plateau for its samples' scatter about
// the model's local slope (from the plateau's centred sums of squares): it minimises the samples
// fit's cost up to the model's curvature across a plateau, and RSS, AIC, R^2 and the standard
// errors count every sample (n is the sample count either way). A plateau whose z spans more
// than 3 times the median plateau's (the settle onto the specimen at the ramp's start, a slip)
// enters as its samples.
// A 1 kHz ramp with 25 ms steps fits ~25 times fewer points. A curve without i_cmd_A is fitted
// on its samples (IndentationResult::fitted_on says which).
// Model-free descriptors (k_fd, window slope) use the chosen model's z_c; the paper variants
// take each repetition's first sample at i >= I_c as depth zero.
//
// Errors: bad parameters and mismatched column sizes throw palp::ConfigError; data the analysis
// cannot use (a NaN/inf sample, too few contact samples, no contact point giving a positive
// stiffness) throws palp::DataError; both name the problem. A value that cannot be computed from
// valid input is an absent Value with a reason, never NaN.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "palp/analysis/contact_models.hpp"

namespace palp::analysis {

/// What the model fits run on: the staircase's plateau means, or every loading sample.
enum class FitOn { plateaus, samples };
const char* fit_on_name(FitOn f);  ///< "plateaus", "samples"

/// Instrument and analysis settings; defaults are the paper's (§II-A, §IV-A), in SI.
struct IndentationParams {
  double force_constant_N_per_A = 2.918;   ///< K_f
  double contact_current_A = 0.5;          ///< I_c
  double spring_N_per_m = 43.9;            ///< k_v (0.0439 N/mm)
  double tip_radius_m = 2.5e-3;            ///< R
  double poisson = 0.5;                    ///< nu of the specimen
  double bias_current_A = 1.0;             ///< I_0: operating point F_0 = K_f (I_0 - I_c)
  std::optional<Thickness> thickness;      ///< finite-thickness correction of Hertz/Sneddon
  double window_lo_m = 0.25e-3;            ///< window for k_fd and the window slope
  double window_hi_m = 0.75e-3;
  double local_half_width_m = 25e-6;       ///< F_o(d): local least squares over d +- this
  std::vector<double> tangent_depths_m{1e-3, 2e-3, 3e-3, 4e-3};
  int min_points = 10;                     ///< fewer loading samples in contact: DataError
  /// The fits on plateau means (needs Curve::i_cmd_A; without it the samples) or on samples.
  FitOn fit_on = FitOn::plateaus;
  /// The force noise floor (rms), e.g. K_f x the current noise; gives each fit a reduced chi^2.
  std::optional<double> force_noise_N;
  /// A K_f(stroke) table instead of the constant: stroke positions from the stroke origin (m,
  /// increasing) and K_f there (N/A), piecewise linear, constant beyond the ends. Empty: the
  /// constant force_constant_N_per_A, the paper's analysis. Only for a recording whose stroke
  /// position is known: stroke_origin_z_m is its z of the stroke origin (the sidecar's
  /// stroke_origin_z_mm). F_0 stays K_f (I_0 - I_c) with the constant.
  std::vector<double> kf_table_stroke_m, kf_table_N_per_A;
  double stroke_origin_z_m = 0.0;
  /// K_f at a recording's z: the table's value there, or the constant.
  double force_constant_at(double z_m) const;
};

/// A recording: probe position and coil current per sample, optional repetition number
/// (any integers; samples of one repetition contiguous and in time order). Empty rep = one rep.
/// Optional commanded current per sample: it marks the staircase's plateaus (FitOn::plateaus);
/// empty = unknown (a LabVIEW export), and the fits run on the samples.
struct Curve {
  Eigen::VectorXd z_m;
  Eigen::VectorXd i_A;
  Eigen::VectorXi rep;
  Eigen::VectorXd i_cmd_A;
};

/// A value or the reason it is absent.
struct Value {
  std::optional<double> value;
  std::string reason;  ///< empty when value is present
  static Value of(double v) { return Value{v, {}}; }
  static Value absent(std::string why) { return Value{std::nullopt, std::move(why)}; }
  explicit operator bool() const { return value.has_value(); }
};

enum class Model { linear, hertz, sneddon };
const char* model_name(Model m);  ///< "linear", "hertz", "sneddon"

/// One fitted model. params/se are in the order of names:
///   linear:  k_N_per_m, contact_z_m
///   hertz / sneddon: Estar_Pa, contact_z_m [, offset_N]
struct ModelFit {
  Model model = Model::linear;
  std::vector<std::string> names;
  Eigen::VectorXd params;
  Eigen::VectorXd se;        ///< standard errors from the Jacobian
  double rss = 0.0;          ///< N^2
  double r2 = 0.0;           ///< of the measured force F
  double aic = 0.0;
  int n = 0;                 ///< loading samples the fit describes
  int n_points = 0;          ///< points it ran on: n, or the plateaus (FitOn::plateaus)
  double rms_residual_N = 0.0;         ///< sqrt(rss / (n - p))
  std::optional<double> reduced_chi2;  ///< rms_residual^2 / force_noise^2, when the noise is given
                                       ///< (near 1: the model is adequate)
  double contact_z_m = 0.0;
  double contact_z_se_m = 0.0;
  std::optional<double> k_N_per_m;     ///< linear
  std::optional<double> Estar_Pa;      ///< hertz / sneddon
  std::optional<double> E_Pa;          ///< from E* with the params' nu
  std::optional<double> offset_N;      ///< only with a baseline
  bool converged = false;
  int iterations = 0;
  std::string contact_method;          ///< how z_c was started (then refined by the fit)
  double radius_m = 2.5e-3;
  std::optional<Thickness> thickness;

  /// Object force of the model at a depth below z_c (no offset), and its analytic derivative.
  double force_N(double depth_m) const;
  double stiffness_N_per_m(double depth_m) const;
};

/// Loading samples (first sample of each repetition up to its peak current) and the rest.
struct Branches {
  std::vector<int> loading;    ///< sample indices
  std::vector<int> unloading;
};

/// F = K_f (i - I_c) for every sample.
Eigen::VectorXd coil_force_N(const Curve& c, const IndentationParams& p);
/// F_o = K_f (i - I_c) - k_v (z - z_c).
Eigen::VectorXd object_force_N(const Curve& c, const IndentationParams& p, double contact_z_m);
Branches loading_branch(const Curve& c);
/// Throws ConfigError on size mismatch or bad params, DataError on a non-finite sample.
void validate(const Curve& c, const IndentationParams& p);

/// Fit on the loading branch (pooled over repetitions). Throws DataError when fewer than
/// p.min_points loading samples reach I_c or no start gives a positive stiffness, ConfigError
/// on bad params.
ModelFit fit_linear(const Curve& c, const IndentationParams& p);
ModelFit fit_hertz(const Curve& c, const IndentationParams& p);
ModelFit fit_sneddon(const Curve& c, const IndentationParams& p);

/// An initial contact estimate (the fits refine z_c; these only say where the data put it).
struct ContactEstimate {
  std::string method;  ///< "first_sample_at_Ic", "baseline_deviation", "piecewise_fit",
                       ///< "ratio_of_variances"
  Value z_m;
};
/// Without a baseline: the first loading sample at i >= I_c (median over repetitions). With a
/// baseline (analysis-notes): on G = K_f (i - I_c) - k_v z (= F_o + const, whatever z_c) of
/// each repetition's loading branch, median over repetitions:
///   baseline_deviation  first sample from which G stays above baseline mean + 5 s.d.
///   piecewise_fit       constant + line, least squares over the breakpoint, on the lowest
///                       5 % of G's rise; z where the line meets the constant
///   ratio_of_variances  argmax of var(next w/2) / var(previous w/2), w = max(10, n/10)
std::vector<ContactEstimate> estimate_contact(const Curve& c, const IndentationParams& p = {});

struct IndentationResult {
  std::optional<ModelFit> linear, hertz, sneddon;
  std::string linear_reason, hertz_reason, sneddon_reason;  ///< why a fit is absent
  std::optional<Model> chosen;           ///< lowest AIC among the fits present
  std::string fit_reason;                ///< why no fit, when none
  bool has_baseline = false;
  FitOn fitted_on = FitOn::samples;      ///< what the fits ran on (plateaus need i_cmd_A)
  int n_fit_points = 0;                  ///< plateaus or samples the fits ran on
  std::vector<ContactEstimate> contact_estimates;  ///< initial estimates (see estimate_contact)
  int n_loading = 0, n_unloading = 0;
  double F0_N = 0.0;                     ///< K_f (I_0 - I_c)
  Value contact_z_m;                     ///< of the chosen model
  Value delta0_m;                        ///< depth where the chosen model's F_o = F_0
  Value k_tangent_at_delta0_N_per_m;     ///< analytic dF_o/ddelta at delta0
  Value k_fd_N_per_m;                    ///< (F_o(hi) - F_o(lo)) / (hi - lo), local LSQ values
  Value k_window_N_per_m;                ///< LSQ slope of F_o over [lo, hi]
  Value k_fd_paper_N_per_m;              ///< k_fd with depths from the first sample at i >= I_c
  Value k_window_paper_N_per_m;          ///< window slope, same depth origin
  std::vector<double> tangent_depths_m;
  std::vector<Value> k_tangent_N_per_m;  ///< chosen model's dF_o/ddelta at tangent_depths_m
};

/// The chosen model's fit (the lowest AIC), or nullptr when no model was fitted.
const ModelFit* chosen_fit(const IndentationResult& r);

/// Standard errors of the chosen model's derived quantities by the delta method through its
/// scale parameter s (k or E*), which the model's force is proportional to: F = s g(delta)
/// (the contact point's covariance with s is not included):
///   delta0: s g(delta0) = F_0  ->  d delta0/ds = -F_0 / (s k_t(delta0))
///   k_t at a fixed depth = s g'(delta)  ->  se = k_t se_s / s
///   k_t at delta0: d/ds = g'(delta0) + s g''(delta0) d delta0/ds (g'' by central difference)
/// E.g. Hertz: se(delta0) = 2/3 delta0 se_s / s, se(k_t(delta0)) = 2/3 k_t se_s / s; linear:
/// se(delta0) = F_0 se_k / k^2, se(k_t) = se_k. Absent, with the reason, where the value is
/// absent or no model (or no finite standard error of s) is there.
struct DerivedSe {
  Value delta0_m, k_tangent_at_delta0_N_per_m;
  std::vector<Value> k_tangent_N_per_m;  ///< at IndentationResult::tangent_depths_m
};
DerivedSe derived_se(const IndentationResult& r);

/// The whole analysis. Throws ConfigError on bad params or mismatched sizes, DataError on a
/// NaN sample or too few contact samples; no contact (no sample with i >= I_c) gives a result
/// whose values are absent with that reason, and a model that cannot be fitted is absent with
/// its reason.
IndentationResult analyze_indentation(const Curve& c, const IndentationParams& p = {});

/// Model-free descriptors over (depth, F_o) pairs, exposed for tests and tools.
/// local_force_N: the least-squares line's value at `at_m` over the samples within
/// +-half_width_m; absent when they span less than half_width_m of depth or lie all on one side
/// beyond half_width_m/2 (a staircase ramp's steps coarser than the window).
Value local_force_N(const Eigen::VectorXd& depth_m, const Eigen::VectorXd& Fo_N, double at_m,
                    double half_width_m);
Value finite_difference_stiffness(const Eigen::VectorXd& depth_m, const Eigen::VectorXd& Fo_N,
                                  const IndentationParams& p);
Value window_slope(const Eigen::VectorXd& depth_m, const Eigen::VectorXd& Fo_N,
                   const IndentationParams& p);

/// Mean and sample s.d. of F_o over repetitions on a common depth grid (loading branches,
/// linear interpolation within each repetition's depth range; count = reps that cover the depth;
/// sd_N is 0 where count < 2 and mean_N is 0 where count = 0: read count first).
struct RepetitionStats {
  Eigen::VectorXd depth_m, mean_N, sd_N;
  Eigen::VectorXi count;
};
RepetitionStats repetition_mean_sd(const Curve& c, const IndentationParams& p, double contact_z_m,
                                   const Eigen::VectorXd& depth_grid_m);

/// Hysteresis of one repetition's load-unload cycle: the loop integral of the coil force over z
/// (the springs' part closes to zero), i.e. the energy dissipated per cycle, and its ratio to the
/// work done on the loading branch by F_o. Absent when the repetition has no unloading branch.
struct Hysteresis {
  Value dissipated_J;
  Value ratio;  ///< dissipated / loading work (0..1)
};
/// One entry per repetition, depths from contact_z_m.
std::vector<Hysteresis> hysteresis(const Curve& c, const IndentationParams& p, double contact_z_m);

/// Each repetition analysed on its own (analyze_indentation on its samples), with the mean and
/// s.d. over repetitions of the main descriptors (a repetition without a value is skipped; one
/// whose data cannot be analysed, e.g. too few points, has every value absent with the reason).
/// Bad params or sizes throw ConfigError, a NaN sample DataError, as analyze_indentation.
struct RepetitionSummary {
  std::vector<IndentationResult> per_rep;
  struct Stat { Value mean, sd; int n = 0; };
  Stat contact_z_m, delta0_m, k_tangent_at_delta0_N_per_m, k_fd_N_per_m, k_window_N_per_m,
      k_fd_paper_N_per_m;
  std::vector<Stat> k_tangent_N_per_m;  ///< at IndentationParams::tangent_depths_m
};
RepetitionSummary analyze_repetitions(const Curve& c, const IndentationParams& p = {});

/// Mean and sample s.d. of a per-repetition scalar (absent values skipped; sd absent below 2).
struct MeanSd {
  Value mean, sd;
  int n = 0;
};
MeanSd mean_sd(const std::vector<Value>& per_rep);

}  // namespace palp::analysis
