// SPDX-License-Identifier: Apache-2.0
// The periodic multisine's frequency response and distortion (frequency_response.hpp): the
// program's start from the commanded current's line phases, whole periods cut on the control
// tick, exact DFT bins per period, averages and period-to-period scatter.
#include <algorithm>
#include <cmath>
#include <string>

#include "frf_internal.hpp"
#include "palp/analysis/frequency_response.hpp"
#include "palp/error.hpp"
#include "palp/protocol/multisine.hpp"
#include "palp/protocol/program_schedule.hpp"
#include "palp/protocol/stream.hpp"

namespace palp::analysis {
namespace {

using detail::strf;
using cplx = std::complex<double>;
constexpr const char* kMultisineWho = "multisine_frf";
using detail::kTwoPi;
using detail::kTurn;
/// Phasor recurrences restart from an exact phase this often (keeps rounding at ~1e-13).
constexpr std::uint32_t kReanchor = 1024;

/// The excited lines: harmonics h_n and phases phi_n (u32 turns), as the device runs them.
struct Lines {
  std::vector<std::uint32_t> h;
  std::vector<std::uint32_t> phase;
  std::uint32_t period_ticks = 0;
};

Lines lines_of(const proto::LoadMultisine& m, std::uint32_t rate_Hz, const char* who) {
  if (!proto::is_supported_control_rate(rate_Hz))
    throw ConfigError(strf("%s: control rate %u Hz is not one the device runs at (20000 or "
                           "40000 Hz)",
                           who, rate_Hz));
  if (!(m.fundamental_Hz > 0))
    throw ConfigError(strf("%s: the program's fundamental_Hz is not > 0", who));
  const std::uint32_t K = proto::multisine_line_count(m.line_first, m.line_last, m.line_step);
  if (K == 0) throw ConfigError(strf("%s: the program excites no line", who));
  Lines l;
  l.period_ticks = proto::multisine_period_ticks(m.fundamental_Hz, rate_Hz);
  for (std::uint32_t n = 0; n < K; ++n) {
    l.h.push_back(static_cast<std::uint32_t>(m.line_first) + n * m.line_step);
    l.phase.push_back(proto::multisine_phase_turns(m.phase_mode, m.phase_seed, n, K));
  }
  if (2ull * l.h.back() >= l.period_ticks)
    throw ConfigError(strf("%s: the highest line is above half the control rate", who));
  return l;
}

/// (2 / N) sum_k y[k] e^{-j 2 pi h (tick_k - origin) / P} over N consecutive samples
/// first, first + 1, ... spaced `interval` ticks (checked by the caller).
cplx dft_bin(const std::vector<double>& y, double scale, std::size_t first, std::size_t N,
             std::int64_t offset_ticks, std::int64_t interval, std::uint32_t h, std::uint32_t P) {
  const auto phase_at = [&](std::size_t k) {  // exact e^{-j 2 pi h tick / P}
    const std::int64_t t = offset_ticks + static_cast<std::int64_t>(k) * interval;
    const auto m = static_cast<std::uint64_t>(((t % P) + P) % P);
    return std::conj(detail::unit_phasor(m * h, P));
  };
  const cplx step = phase_at(1) * std::conj(phase_at(0));
  cplx acc = 0, e = 0;
  for (std::size_t k = 0; k < N; ++k) {
    e = (k % kReanchor == 0) ? phase_at(k) : e * step;
    acc += y[first + k] * e;
  }
  return acc * (2.0 * scale / static_cast<double>(N));
}

/// The program's first tick (absolute), from the commanded current over one period starting at
/// its first visible change: every line's phase there against the program's phases gives the
/// delay since the start (the lowest line resolves it, all lines refine it).
std::int64_t program_start_tick(const detail::TickedRecording& r, const proto::LoadMultisine& m,
                                const Lines& l) {
  const std::int64_t d = r.interval_ticks;
  const std::size_t N = l.period_ticks / static_cast<std::uint32_t>(d);
  const double K = static_cast<double>(l.h.size());
  const double threshold =
      std::max(3 * proto::kCurrentLsb_A, 0.1 * m.line_amplitude_A * std::sqrt(K / 2));
  const std::size_t r0 = detail::first_departure(r, threshold, kMultisineWho);
  if (r0 + N > r.size() || r.tick[r0 + N - 1] - r.tick[r0] != static_cast<std::int64_t>(N - 1) * d)
    throw DataError(strf("%s: the recording has no whole period of the commanded current "
                           "after its first change (at %.6f s)",
                           kMultisineWho, r.rec->t_s[r0]));
  double amplitude = 0, sum_hr = 0, sum_hh = 0, delta0 = 0;
  std::vector<double> turns(l.h.size());
  for (std::size_t n = 0; n < l.h.size(); ++n) {
    const cplx c = dft_bin(*r.rec->i_cmd_A, 1.0, r0, N, 0, d, l.h[n], l.period_ticks);
    amplitude += std::abs(c) / K;
    // c = A e^{j 2 pi (phi_n + h_n delta / P)}, delta = tick[r0] - t0 >= 0
    turns[n] = std::arg(c) / kTwoPi - l.phase[n] / kTurn;
  }
  if (std::abs(amplitude - m.line_amplitude_A) > 0.05 * m.line_amplitude_A + proto::kCurrentLsb_A)
    throw DataError(strf("%s: the commanded current does not show this multisine (line "
                           "amplitude %.5f A, the program's %.5f A)",
                           kMultisineWho, amplitude, static_cast<double>(m.line_amplitude_A)));
  {
    double t = turns[0] - std::floor(turns[0] + 0.1);  // [-0.1, 0.9) of the lowest line
    delta0 = t * l.period_ticks / l.h[0];
  }
  for (std::size_t n = 0; n < l.h.size(); ++n) {
    double res = turns[n] - l.h[n] * delta0 / l.period_ticks;
    res -= std::round(res);
    sum_hr += l.h[n] * res;
    sum_hh += static_cast<double>(l.h[n]) * l.h[n];
  }
  const double delta = delta0 + l.period_ticks * sum_hr / sum_hh;
  return static_cast<std::int64_t>(std::llround(static_cast<double>(r.tick[r0]) - delta));
}

/// Per-period phasors of one signal at a set of harmonics: [line][period].
using PeriodPhasors = std::vector<std::vector<cplx>>;

double rms(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return v.empty() ? 0.0 : std::sqrt(s / static_cast<double>(v.size()));
}

}  // namespace

double program_duration_s(const proto::LoadMultisine& program, std::uint32_t control_rate_Hz) {
  const Lines l = lines_of(program, control_rate_Hz, "program_duration_s");
  if (program.periods == 0)
    throw ConfigError("program_duration_s: a multisine with periods 0 runs until stopped");
  return static_cast<double>(program.periods) * l.period_ticks / control_rate_Hz;
}

double multisine_unit_peak(const proto::LoadMultisine& program, std::uint32_t control_rate_Hz) {
  const Lines l = lines_of(program, control_rate_Hz, "multisine_unit_peak");
  const std::uint32_t P = l.period_ticks;
  std::vector<cplx> e(l.h.size()), step(l.h.size());
  for (std::size_t n = 0; n < l.h.size(); ++n) step[n] = detail::unit_phasor(l.h[n], P);
  double peak = 0;
  for (std::uint32_t k = 0; k < P; ++k) {
    double x = 0;
    if (k % kReanchor == 0) {  // exact phases: phi_n + h_n k / P turns
      for (std::size_t n = 0; n < l.h.size(); ++n)
        e[n] = detail::unit_phasor_u32(l.phase[n]) *
               detail::unit_phasor(static_cast<std::uint64_t>(l.h[n]) * k % P, P);
    } else {
      for (std::size_t n = 0; n < l.h.size(); ++n) e[n] *= step[n];
    }
    for (const cplx& v : e) x += v.real();
    peak = std::max(peak, std::abs(x));
  }
  return peak;
}

Frf multisine_frf(const Recording& rec, const proto::LoadMultisine& program,
                  std::uint32_t control_rate_Hz, const FrfOptions& options) {
  const Lines l = lines_of(program, control_rate_Hz, kMultisineWho);
  const detail::TickedRecording r = detail::ticked(rec, control_rate_Hz, kMultisineWho);
  detail::check_force_constant(options, kMultisineWho);
  if (!(program.line_amplitude_A > 0))
    throw ConfigError(strf("%s: the program's line_amplitude_A is not > 0", kMultisineWho));
  if (options.multisine_discard_periods < 0)
    throw ConfigError(strf("%s: multisine_discard_periods is negative", kMultisineWho));
  const std::uint32_t P = l.period_ticks;
  const std::int64_t d = r.interval_ticks;
  if (P % d != 0)
    throw DataError(strf("%s: the stream's sample interval (%lld ticks) does not divide the "
                           "period (%u ticks): choose a decimation that divides it",
                           kMultisineWho, static_cast<long long>(d), P));
  const auto N = static_cast<std::size_t>(P / d);
  const std::int64_t t0 = program_start_tick(r, program, l);
  const double rate = control_rate_Hz;

  // whole periods in the recording, from the discarded ones on
  const auto periods_recorded = static_cast<std::int64_t>(
      std::max<std::int64_t>(0, r.tick.back() - t0 + d) / P);
  const std::int64_t program_periods = program.periods;
  if (program_periods > 0 && periods_recorded < program_periods)
    throw DataError(strf("%s: the recording ends at %.6f s, before the program does (%.6f s; "
                           "it started at %.6f s)",
                           kMultisineWho, rec.t_s.back(),
                           static_cast<double>(t0 + program_periods * P) / rate,
                           static_cast<double>(t0) / rate));
  const std::int64_t last = program_periods > 0 ? program_periods : periods_recorded;
  const std::int64_t discard = options.multisine_discard_periods;
  if (last <= discard)
    throw DataError(strf("%s: %lld whole periods recorded and %lld discarded: none left to "
                           "measure",
                           kMultisineWho, static_cast<long long>(last), static_cast<long long>(discard)));
  // the first sample of every whole measured period (N samples spaced d); a period with a gap
  // in the stream is left out and the notes say so
  std::vector<std::size_t> first;
  std::vector<std::int64_t> offset;  // of the period's first sample from its start, ticks
  std::vector<std::string> skipped;
  for (std::int64_t p = discard; p < last; ++p) {
    const std::int64_t start = t0 + p * P;
    const auto it = std::lower_bound(r.tick.begin(), r.tick.end(), start);
    const auto k = static_cast<std::size_t>(it - r.tick.begin());
    if (k + N > r.size() || r.tick[k + N - 1] - r.tick[k] != static_cast<std::int64_t>(N - 1) * d ||
        r.tick[k] - start >= d) {
      skipped.push_back(strf("period %lld (from %.6f s) has a gap in the stream: left out",
                             static_cast<long long>(p), static_cast<double>(start) / rate));
      continue;
    }
    first.push_back(k);
    offset.push_back(r.tick[k] - start);
  }
  if (first.empty())
    throw DataError(strf("%s: every measured period has a gap in the stream", kMultisineWho));
  const std::size_t M = first.size();

  // harmonics to transform: the excited lines, then the empty ones between them
  std::vector<std::uint32_t> harmonics = l.h;
  std::vector<std::uint32_t> empty;
  for (std::uint32_t h = l.h.front() + 1; h < l.h.back(); ++h)
    if (!std::binary_search(l.h.begin(), l.h.end(), h)) empty.push_back(h);
  harmonics.insert(harmonics.end(), empty.begin(), empty.end());
  PeriodPhasors I(harmonics.size(), std::vector<cplx>(M)), Z = I;
  double z_sum = 0;
  for (std::size_t p = 0; p < M; ++p) {
    for (std::size_t k = 0; k < N; ++k) z_sum += rec.z_mm[first[p] + k];
    for (std::size_t n = 0; n < harmonics.size(); ++n) {
      Z[n][p] = dft_bin(rec.z_mm, 1e-3, first[p], N, offset[p], d, harmonics[n], P);
      if (n < l.h.size())
        I[n][p] = dft_bin(rec.i_A, 1.0, first[p], N, offset[p], d, harmonics[n], P);
    }
  }
  const double z_mean_m = z_sum / static_cast<double>(M * N) * 1e-3;
  const double kf = detail::force_constant_at(options, z_mean_m);
  const auto mean = [M](const std::vector<cplx>& v) {
    cplx s = 0;
    for (const cplx& x : v) s += x;
    return s / static_cast<double>(M);
  };

  Frf out;
  out.method = "multisine";
  out.line_spacing_Hz = program.line_step * rate / P;
  out.device_time_s = static_cast<double>(last) * P / rate;
  std::vector<double> excited_abs, residual_var;
  for (std::size_t n = 0; n < l.h.size(); ++n) {
    FrfLine line;
    line.f_Hz = l.h[n] * rate / P;
    line.z_mean_m = z_mean_m;
    line.F_N = kf * mean(I[n]);
    line.Z_m = mean(Z[n]);
    line.G_m_per_N = line.Z_m / line.F_N;
    if (M >= 2) {  // scatter of Z_p - G F_p over the periods
      double v = 0;
      for (std::size_t p = 0; p < M; ++p) v += std::norm(Z[n][p] - line.G_m_per_N * kf * I[n][p]);
      residual_var.push_back(v / static_cast<double>(M - 1));
    }
    excited_abs.push_back(std::abs(line.Z_m));
    out.lines.push_back(line);
  }
  // Each line's scatter has only 2 (M - 1) degrees of freedom (2 with the default two periods):
  // weights from it alone are erratic (a line with a small scatter by chance dominates the fit).
  // The noise varies slowly with frequency, so each line's variance is pooled over its
  // kPoolHalfWidth neighbours on each side (15 lines with the default, 28 degrees of freedom).
  if (M >= 2) {
    constexpr std::size_t kPoolHalfWidth = 7;
    const std::size_t L = residual_var.size();
    for (std::size_t n = 0; n < L; ++n) {
      const std::size_t a = n >= kPoolHalfWidth ? n - kPoolHalfWidth : 0;
      const std::size_t b = std::min(L, n + kPoolHalfWidth + 1);
      double v = 0;
      for (std::size_t k = a; k < b; ++k) v += residual_var[k];
      v /= static_cast<double>(b - a);
      out.lines[n].sigma_m_per_N = std::sqrt(v / (2.0 * static_cast<double>(M))) / std::abs(out.lines[n].F_N);
    }
  }
  out.notes.insert(out.notes.end(), skipped.begin(), skipped.end());
  if (M < 2)
    out.notes.push_back("one measured period: sigma is 0 (record two or more periods after the "
                        "transient to measure the noise)");

  FrfDistortion dist;
  std::vector<double> even_abs, odd_abs, noise;
  for (std::size_t n = l.h.size(); n < harmonics.size(); ++n) {
    const cplx zm = mean(Z[n]);
    (harmonics[n] % 2 == 0 ? even_abs : odd_abs).push_back(std::abs(zm));
    if (M >= 2) {
      double v = 0;
      for (const cplx& z : Z[n]) v += std::norm(z - zm);
      noise.push_back(std::sqrt(v / static_cast<double>(M - 1) / static_cast<double>(M)));
    }
  }
  dist.excited_rms_m = rms(excited_abs);
  dist.even_rms_m = rms(even_abs);
  dist.odd_rms_m = rms(odd_abs);
  dist.noise_rms_m = rms(noise);
  if (dist.excited_rms_m > 0) {
    dist.even_ratio = dist.even_rms_m / dist.excited_rms_m;
    dist.odd_ratio = dist.odd_rms_m / dist.excited_rms_m;
  }
  // distortion counts when above the limit and clear of the noise on the same lines
  const bool even_large = dist.even_ratio > options.distortion_limit &&
                          dist.even_rms_m > 2 * dist.noise_rms_m;
  const bool odd_large = dist.odd_ratio > options.distortion_limit &&
                         dist.odd_rms_m > 2 * dist.noise_rms_m;
  if (even_large || odd_large) {
    const bool even = even_large && (!odd_large || dist.even_ratio >= dist.odd_ratio);
    dist.too_large = true;
    dist.warning = strf("the multisine's %s-order distortion is %.1f %% of the excited level "
                        "(limit %.1f %%): the response is not linear at this amplitude; use a "
                        "smaller line amplitude",
                        even ? "even" : "odd", 100 * (even ? dist.even_ratio : dist.odd_ratio),
                        100 * options.distortion_limit);
  }
  if (empty.empty())
    out.notes.push_back("no empty lines between the excited ones: no distortion estimate");
  else
    out.notes.push_back(strf("one excited line every %.4g Hz (1 in %u lines of the %.4g Hz period "
                             "grid): coarser than a stepped sine's 0.05 Hz grid on purpose, the empty "
                             "lines between measure noise and distortion in the same run",
                             out.line_spacing_Hz, static_cast<unsigned>(program.line_step), rate / P));
  out.distortion = dist;
  return out;
}

}  // namespace palp::analysis
