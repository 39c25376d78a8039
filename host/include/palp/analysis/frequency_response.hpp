// SPDX-License-Identifier: Apache-2.0
// Nonparametric frequency responses from a recording (issue 7, analysis-notes.md "Nonparametric
// FRF"): the device's stepped sine and periodic multisine, cut exactly as the device ran them
// (palp/protocol/program_schedule.hpp), and the multisine's true peak for the contact checks.
//
// Input is a recording in lab units (recording.hpp: t_s device time, i_A measured current, z_mm,
// i_cmd_A commanded current) holding the samples the program drove; the program's parameters
// are the Load* message the device ran, and the device's control rate. F = K_f I from the
// measured current with the force constant of `FrfOptions` (the constant, or a K_f(stroke) table
// at each line's mean position).
//
// The recording may start before the program (the commanded current constant until it starts)
// or with its first samples (only those with program_running, as the experiments record);
// t_s must lie on the control-tick grid (device time). FrfLine::f_Hz is the frequency the
// device realised (its phase increment, or harmonic * rate / period ticks).
//
// Stepped sine: the program's start is found to the control tick from the commanded current's
// phase on the first line (the device starts every line at phase 0), each line's measured
// cycles are cut from the schedule, and current and position are each fitted with
// c + a cos(wt) + b sin(wt) (+ a linear drift) over that window (least squares: no leakage from
// the bias when the window is not a whole number of samples); sigma from the fit residuals.
// Multisine: the transient periods are dropped, every following whole period is transformed at
// the excited lines and the empty ones between the first and the last (exact DFT bins: a period
// is a whole number of samples), the phasors are averaged over periods, and the period-to-period
// variance gives each line's sigma (P >= 2 measured periods; with one period sigma is 0 and the
// note says so). The variance is pooled over each line's 7 neighbours on either side: two periods
// give one line only 2 degrees of freedom, and weights that noisy made the fit erratic (b_v off by
// up to 12 % in free air on palp-sim, normalised cost up to 30; pooled: within 1.5 %, cost ~1). A period with a gap in the stream is left out, and a note says which.
//
// Errors, naming the problem: DataError for a recording that cannot give the response (too few
// samples for a line, a recording that does not cover the program or lacks i_cmd_A, stream rate
// not dividing the period, NaN or off-grid times in the data ...); ConfigError for bad settings
// or programs (a control rate the device does not run, no line, a negative discard ...).
#pragma once

#include <cstdint>
#include <vector>

#include "palp/analysis/frf.hpp"
#include "palp/protocol/messages.hpp"
#include "palp/recording_types.hpp"

namespace palp::analysis {

/// How forces are computed from currents.
struct FrfOptions {
  double force_constant_N_per_A = 2.918;  ///< K_f (paper §II-A), used when the table is empty
  /// Optional K_f(stroke) table (as IndentationParams): stroke positions (m, increasing) from the
  /// stroke origin, K_f there (N/A); a line uses K_f at its mean position.
  std::vector<double> kf_table_stroke_m, kf_table_N_per_A;
  double stroke_origin_z_m = 0.0;
  /// Multisine: whole periods dropped at the start (the transient).
  int multisine_discard_periods = 1;
  /// Even or odd distortion above this ratio of the excited level sets FrfDistortion::too_large
  /// (when it also stands above twice the noise floor, noise_rms_m: noise is not distortion).
  double distortion_limit = 0.05;
};

/// The stepped sine's response, one line per frequency of the program.
Frf stepped_sine_frf(const Recording& rec, const proto::LoadSweep& program,
                     std::uint32_t control_rate_Hz, const FrfOptions& options = {});

/// The multisine's response at its excited lines, with the distortion of its empty lines.
Frf multisine_frf(const Recording& rec, const proto::LoadMultisine& program,
                  std::uint32_t control_rate_Hz, const FrfOptions& options = {});

/// Largest |deviation from offset_A| of the multisine the device plays with line amplitude 1 A,
/// evaluated on every control tick of one period (so the true peak, not an estimate). Scale the
/// line amplitude by peak_A / this to reach a wanted peak.
double multisine_unit_peak(const proto::LoadMultisine& program, std::uint32_t control_rate_Hz);

/// Device time of a program, s (exactly as the device runs it). ConfigError for a multisine
/// with periods 0 (it runs until stopped) or a control rate the device does not run at.
double program_duration_s(const proto::LoadSweep& program, std::uint32_t control_rate_Hz);
double program_duration_s(const proto::LoadMultisine& program, std::uint32_t control_rate_Hz);

}  // namespace palp::analysis
