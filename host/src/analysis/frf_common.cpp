// SPDX-License-Identifier: Apache-2.0
// The frequency-response sources' shared checks and helpers (frf_internal.hpp).
#include "frf_internal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <map>

#include "palp/analysis/indentation.hpp"
#include "palp/error.hpp"
#include "palp/protocol/program_schedule.hpp"

namespace palp::analysis::detail {
namespace {
/// A sample's t_s * rate must be this close to an integer (device time is whole ticks, written
/// in microseconds: exact at 20 and 40 kHz).
constexpr double kGridTolerance_ticks = 0.01;

void check_finite(const std::vector<double>& v, const char* column, const char* who) {
  for (std::size_t k = 0; k < v.size(); ++k)
    if (!std::isfinite(v[k]))
      throw DataError(strf("%s: %s is not a finite number at sample %zu", who, column, k));
}
}  // namespace

std::string strf(const char* format, ...) {
  va_list args;
  va_start(args, format);
  va_list copy;
  va_copy(copy, args);
  const int n = std::vsnprintf(nullptr, 0, format, copy);
  va_end(copy);
  std::string s(n > 0 ? static_cast<std::size_t>(n) : 0, '\0');
  if (n > 0) std::vsnprintf(s.data(), s.size() + 1, format, args);
  va_end(args);
  return s;
}

TickedRecording ticked(const Recording& rec, std::uint32_t control_rate_Hz, const char* who) {
  if (!proto::is_supported_control_rate(control_rate_Hz))
    throw ConfigError(strf("%s: control rate %u Hz is not one the device runs at (20000 or "
                           "40000 Hz)",
                           who, control_rate_Hz));
  if (!rec.i_cmd_A)
    throw DataError(strf("%s: the recording has no i_cmd_A column (the commanded current "
                           "places the program in it)",
                           who));
  const std::size_t n = rec.size();
  if (rec.i_A.size() != n || rec.z_mm.size() != n || rec.i_cmd_A->size() != n)
    throw DataError(strf("%s: the recording's columns differ in length", who));
  if (n < 2) throw DataError(strf("%s: the recording has %zu samples", who, n));
  check_finite(rec.t_s, "t_s", who);
  check_finite(rec.i_A, "i_A", who);
  check_finite(rec.z_mm, "z_mm", who);
  check_finite(*rec.i_cmd_A, "i_cmd_A", who);

  TickedRecording r;
  r.rec = &rec;
  r.rate_Hz = control_rate_Hz;
  r.tick.resize(n);
  std::map<std::int64_t, std::size_t> intervals;
  for (std::size_t k = 0; k < n; ++k) {
    const double ticks = rec.t_s[k] * control_rate_Hz;
    const double whole = std::round(ticks);
    if (std::abs(ticks - whole) > kGridTolerance_ticks)
      throw DataError(strf("%s: t_s at sample %zu (%.6f s) is not on the control-tick grid of "
                             "%u Hz: is the control rate right?",
                             who, k, rec.t_s[k], control_rate_Hz));
    r.tick[k] = static_cast<std::int64_t>(whole);
    if (k > 0) {
      if (r.tick[k] <= r.tick[k - 1])
        throw DataError(strf("%s: t_s does not increase at sample %zu", who, k));
      ++intervals[r.tick[k] - r.tick[k - 1]];
    }
  }
  r.interval_ticks = std::max_element(intervals.begin(), intervals.end(), [](auto& a, auto& b) {
                       return a.second < b.second;
                     })->first;
  return r;
}

std::size_t first_departure(const TickedRecording& r, double threshold_A, const char* who) {
  const std::vector<double>& c = *r.rec->i_cmd_A;
  for (std::size_t k = 1; k < c.size(); ++k)
    if (std::abs(c[k] - c[0]) > threshold_A) return k;
  throw DataError(strf("%s: the commanded current (i_cmd_A) never changes: the recording does "
                         "not show the program",
                         who));
}

std::complex<double> unit_phasor(std::uint64_t numerator, std::uint64_t denominator) {
  const double turns =
      static_cast<double>(numerator % denominator) / static_cast<double>(denominator);
  return std::polar(1.0, kTwoPi * turns);
}

std::complex<double> unit_phasor_u32(std::uint32_t phase) {
  return std::polar(1.0, kTwoPi * (static_cast<double>(phase) / 4294967296.0));
}

double force_constant_at(const FrfOptions& o, double z_m) {
  IndentationParams p;  // one interpolation of a K_f table for every analysis
  p.force_constant_N_per_A = o.force_constant_N_per_A;
  p.kf_table_stroke_m = o.kf_table_stroke_m;
  p.kf_table_N_per_A = o.kf_table_N_per_A;
  p.stroke_origin_z_m = o.stroke_origin_z_m;
  return p.force_constant_at(z_m);
}

void check_force_constant(const FrfOptions& o, const char* who) {
  const auto& s = o.kf_table_stroke_m;
  const auto& k = o.kf_table_N_per_A;
  if (s.size() != k.size())
    throw ConfigError(strf("%s: the K_f table has %zu positions and %zu values", who, s.size(),
                           k.size()));
  for (std::size_t j = 0; j < s.size(); ++j) {
    if (!std::isfinite(s[j]) || !std::isfinite(k[j]) || !(k[j] > 0) ||
        (j > 0 && !(s[j] > s[j - 1])))
      throw ConfigError(strf("%s: the K_f table needs increasing positions and finite values "
                             "> 0 (entry %zu)",
                             who, j));
  }
  if (s.empty() && !(std::isfinite(o.force_constant_N_per_A) && o.force_constant_N_per_A > 0))
    throw ConfigError(strf("%s: the force constant must be finite and > 0", who));
}

double mean_at(const std::vector<double>& values, const std::vector<std::size_t>& idx) {
  double sum = 0;
  for (std::size_t k : idx) sum += values[k];
  return idx.empty() ? 0.0 : sum / static_cast<double>(idx.size());
}

}  // namespace palp::analysis::detail
