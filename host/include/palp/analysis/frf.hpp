// SPDX-License-Identifier: Apache-2.0
// A measured frequency response (issue 7): the types every frequency-response function shares.
//
// G = Z / F in m/N: force F = K_f I in (the measured coil current times the force constant),
// displacement Z out. Phasors follow x(t) = Re{X e^{j omega t}} with X the peak amplitude, so a
// passive system has Im G <= 0 (the displacement lags the force). SI units throughout.
#pragma once

#include <complex>
#include <optional>
#include <string>
#include <vector>

namespace palp::analysis {

/// One excited line of a frequency response.
struct FrfLine {
  double f_Hz = 0;                  ///< the line's frequency
  std::complex<double> G_m_per_N;   ///< Z / F
  /// Standard deviation of Re G and of Im G (each) from the measurement's own noise, m/N;
  /// 0 when unknown (a table without noise columns). The fits weight lines by 1/sigma^2.
  double sigma_m_per_N = 0;
  std::complex<double> F_N;         ///< force phasor (peak), N; 0 when unknown (a table)
  std::complex<double> Z_m;         ///< displacement phasor (peak), m; 0 when unknown
  double z_mean_m = 0;              ///< mean position over the line's window, m (0: unknown)
};

/// Non-excited lines of a multisine (noise and nonlinear distortion in the same run). With the
/// excited lines at 4k+1, even-order distortion lands on lines 4k and 4k+2, odd-order on 4k+3
/// (and on the excited lines themselves).
struct FrfDistortion {
  /// rms over the band's excited lines of |Z|, m
  double excited_rms_m = 0;
  /// rms of |Z| over the empty lines that collect even- / odd-order products, m
  double even_rms_m = 0, odd_rms_m = 0;
  /// rms of the period-to-period noise of Z over the empty lines, m: the noise of the averaged
  /// Z (sd over periods / sqrt(periods)), the floor even_rms and odd_rms stand on
  double noise_rms_m = 0;
  /// even_rms / excited_rms and odd_rms / excited_rms (dimensionless)
  double even_ratio = 0, odd_ratio = 0;
  /// set when the distortion stands above the small-signal limit (see frequency_response.hpp):
  /// then `warning` says so in one sentence that names the ratio and suggests a smaller amplitude
  bool too_large = false;
  std::string warning;
};

/// A frequency response with how it was measured.
struct Frf {
  std::string method;              ///< "stepped_sine", "multisine" or "table"
  std::vector<FrfLine> lines;      ///< excited lines, increasing frequency
  double line_spacing_Hz = 0;      ///< between excited lines (0.05 stepped, 0.2 default multisine)
  double device_time_s = 0;        ///< the excitation's device time (0 for a table)
  std::optional<FrfDistortion> distortion;  ///< multisine only
  /// Sentences for the user, e.g. that the multisine's grid is coarser than the stepped sine's
  /// on purpose, or that most Im G of a table are positive.
  std::vector<std::string> notes;
};

}  // namespace palp::analysis
