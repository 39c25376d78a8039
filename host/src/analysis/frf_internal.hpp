// SPDX-License-Identifier: Apache-2.0
// Shared by the frequency-response and K_f-calibration sources (private): a recording checked
// and placed on the device's control-tick grid, the program start from the commanded current,
// exact tone phases, and the force constant.
#pragma once

#include <complex>
#include <cstdint>
#include <string>
#include <vector>

#include "palp/analysis/frequency_response.hpp"
#include "palp/recording_types.hpp"

namespace palp::analysis::detail {

inline constexpr double kTwoPi = 6.283185307179586476925;
inline constexpr double kTurn = 4294967296.0;  ///< 2^32: the programs' phase accumulators wrap here

/// printf into a std::string (for error texts with numbers).
[[gnu::format(printf, 1, 2)]] std::string strf(const char* format, ...);

/// A recording on the control-tick grid: tick[k] = t_s[k] * rate (an integer: device time is
/// whole ticks). Checked: i_cmd_A present, no NaN, time increasing, every t_s on the grid.
struct TickedRecording {
  const Recording* rec = nullptr;
  std::vector<std::int64_t> tick;
  std::int64_t interval_ticks = 0;  ///< the stream's sample interval (its most common one)
  std::uint32_t rate_Hz = 0;
  std::size_t size() const { return tick.size(); }
};

/// ConfigError "<who>: ..." for an unsupported rate or a recording that fails the checks.
TickedRecording ticked(const Recording& rec, std::uint32_t control_rate_Hz, const char* who);

/// First sample whose commanded current differs from the first sample's by more than
/// threshold_A (the program's first visible tick); ConfigError when there is none.
std::size_t first_departure(const TickedRecording& r, double threshold_A, const char* who);

/// exp(j 2 pi turns) for turns = numerator / denominator, exact in the integers (no rounding
/// grows with the tick count).
std::complex<double> unit_phasor(std::uint64_t numerator, std::uint64_t denominator);
/// exp(j 2 pi turns) for a u32 phase (turns = phase / 2^32).
std::complex<double> unit_phasor_u32(std::uint32_t phase);

/// K_f at position z_m: the options' table at z_m - stroke_origin_z_m, or the constant.
double force_constant_at(const FrfOptions& o, double z_m);
/// ConfigError "<who>: ..." for a table that is not usable (sizes, order, values).
void check_force_constant(const FrfOptions& o, const char* who);

/// Mean of values[idx].
double mean_at(const std::vector<double>& values, const std::vector<std::size_t>& idx);

}  // namespace palp::analysis::detail
