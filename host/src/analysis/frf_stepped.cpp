// SPDX-License-Identifier: Apache-2.0
// The stepped sine's frequency response (frequency_response.hpp): the program's start from the
// commanded current on the first line, each line's measured cycles cut from the device's
// schedule (program_schedule.hpp), and a least-squares sinusoid per line.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "frf_internal.hpp"
#include "palp/analysis/frequency_response.hpp"
#include "palp/error.hpp"
#include "palp/protocol/program_schedule.hpp"
#include "palp/protocol/stream.hpp"

namespace palp::analysis {
namespace {

using detail::strf;
constexpr const char* kSteppedWho = "stepped_sine_frf";
using detail::kTwoPi;
using detail::kTurn;

/// A line's ticks from the program start: [begin, end), measured from measure_begin.
struct LineTicks {
  std::uint32_t increment = 0, measure_cycles = 0;
  std::int64_t begin = 0, measure_begin = 0, end = 0;
};

std::vector<LineTicks> schedule(const proto::LoadSweep& m, std::uint32_t rate_Hz) {
  const proto::SweepPlan plan = proto::sweep_plan(m, rate_Hz);
  std::vector<LineTicks> lines(plan.lines);
  std::int64_t t = 0;
  for (std::uint32_t j = 0; j < plan.lines; ++j) {
    const proto::SweepLine l = proto::sweep_line(plan, j);
    lines[j].increment = l.increment;
    lines[j].measure_cycles = plan.measure_cycles;
    lines[j].begin = t;
    lines[j].measure_begin = t + static_cast<std::int64_t>(proto::sweep_settle_ticks(l));
    t += static_cast<std::int64_t>(proto::sweep_line_ticks(l));
    lines[j].end = t;
  }
  return lines;
}

/// y = c + d tau + a cos(phi) + b sin(phi) over the samples idx, phi the line's exact tone phase
/// at (tick - begin), tau the time from the window's middle. X = a - j b (x = Re{X e^{j phi}}).
struct SineFit {
  std::complex<double> X;
  double sigma = 0;  ///< standard deviation of Re X and of Im X (each)
  double mean = 0;   ///< c: the mean over the window, free of the sinusoid's leakage
  double amplitude() const { return std::abs(X); }
};

SineFit fit_sine(const std::vector<double>& y, double scale, const std::vector<std::size_t>& idx,
                 const std::vector<std::int64_t>& tick, std::int64_t begin,
                 std::uint32_t increment, std::uint32_t rate_Hz, bool drift) {
  const auto n = static_cast<Eigen::Index>(idx.size());
  const Eigen::Index p = drift ? 4 : 3;
  const double mid = 0.5 * static_cast<double>(tick[idx.front()] + tick[idx.back()]);
  Eigen::MatrixXd A(n, p);
  Eigen::VectorXd v(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    const std::size_t k = idx[static_cast<std::size_t>(r)];
    const auto phase = static_cast<std::uint32_t>(
        static_cast<std::uint64_t>(tick[k] - begin) * increment);  // mod 2^32, exact
    const std::complex<double> e = detail::unit_phasor_u32(phase);
    A(r, 0) = e.real();
    A(r, 1) = e.imag();
    A(r, 2) = 1.0;
    if (drift) A(r, 3) = (static_cast<double>(tick[k]) - mid) / rate_Hz;
    v[r] = y[k] * scale;
  }
  const Eigen::VectorXd c = A.colPivHouseholderQr().solve(v);
  SineFit f;
  f.X = {c[0], -c[1]};
  f.mean = c[2];
  const double rss = (A * c - v).squaredNorm();
  const double s2 = n > p ? rss / static_cast<double>(n - p) : 0.0;
  const Eigen::MatrixXd cov = (A.transpose() * A).inverse() * s2;
  f.sigma = std::sqrt(0.5 * (cov(0, 0) + cov(1, 1)));
  return f;
}

/// Indices of the samples whose tick lies in [lo, hi) (tick increasing).
std::vector<std::size_t> samples_in(const std::vector<std::int64_t>& tick, std::int64_t lo,
                                    std::int64_t hi) {
  const auto b = std::lower_bound(tick.begin(), tick.end(), lo);
  const auto e = std::lower_bound(b, tick.end(), hi);
  std::vector<std::size_t> idx;
  idx.reserve(static_cast<std::size_t>(e - b));
  for (auto it = b; it != e; ++it) idx.push_back(static_cast<std::size_t>(it - tick.begin()));
  return idx;
}

/// The program's first tick (absolute): the first line's phase in the commanded current, from
/// its first visible change on, rounded to the control tick.
std::int64_t program_start_tick(const detail::TickedRecording& r, const proto::LoadSweep& m,
                                const LineTicks& first) {
  const double amplitude = m.amplitude_A;
  const std::size_t r0 =
      detail::first_departure(r, std::max(3 * proto::kCurrentLsb_A, 0.05 * amplitude), kSteppedWho);
  // the program started after sample r0 - 1 went out (or just before it); 85 % of the first
  // line from there stays inside the first line
  const std::int64_t from = r.tick[r0];
  const auto span = static_cast<std::int64_t>(0.85 * static_cast<double>(first.end));
  const std::vector<std::size_t> idx = samples_in(r.tick, from, r.tick[r0 - 1] + span);
  if (idx.size() < 8)
    throw DataError(strf("%s: the first line has %zu samples of the commanded current at the "
                           "recording's start (need 8)",
                           kSteppedWho, idx.size()));
  const SineFit f = fit_sine(*r.rec->i_cmd_A, 1.0, idx, r.tick, from, first.increment, r.rate_Hz,
                             false);
  // i_cmd = offset + A sin(w (t - t0)) = Re{X e^{j w (t - from)}} with X = -j A e^{j w delta},
  // delta = from - t0 >= 0 ticks
  if (std::abs(f.amplitude() - amplitude) > 0.05 * amplitude + 3 * proto::kCurrentLsb_A)
    throw DataError(strf("%s: the commanded current does not show the sweep's first line "
                           "(amplitude %.4f A at %.4f Hz, the program's %.4f A)",
                           kSteppedWho, f.amplitude(),
                           first.increment * static_cast<double>(r.rate_Hz) / kTurn, amplitude));
  double turns = std::arg(f.X * std::complex<double>(0, 1)) / kTwoPi;  // w delta, in turns
  turns -= std::floor(turns + 0.1);                                      // [-0.1, 0.9)
  const double delta_ticks = turns * kTurn / first.increment;
  return static_cast<std::int64_t>(std::llround(static_cast<double>(from) - delta_ticks));
}

}  // namespace

double program_duration_s(const proto::LoadSweep& program, std::uint32_t control_rate_Hz) {
  if (!proto::is_supported_control_rate(control_rate_Hz))
    throw ConfigError(strf("program_duration_s: control rate %u Hz is not one the device runs "
                           "at (20000 or 40000 Hz)",
                           control_rate_Hz));
  return static_cast<double>(proto::sweep_total_ticks(proto::sweep_plan(program,
                                                                        control_rate_Hz))) /
         control_rate_Hz;
}

Frf stepped_sine_frf(const Recording& rec, const proto::LoadSweep& program,
                     std::uint32_t control_rate_Hz, const FrfOptions& options) {
  const detail::TickedRecording r = detail::ticked(rec, control_rate_Hz, kSteppedWho);
  detail::check_force_constant(options, kSteppedWho);
  if (!(program.amplitude_A > 0))
    throw ConfigError(strf("%s: the program's amplitude_A is not > 0", kSteppedWho));
  const std::vector<LineTicks> lines = schedule(program, control_rate_Hz);
  const std::int64_t t0 = program_start_tick(r, program, lines.front());
  const std::int64_t total = lines.back().end;
  const double rate = control_rate_Hz;
  if (r.tick.back() - t0 < total - r.interval_ticks)
    throw DataError(strf("%s: the recording ends at %.6f s, before the program does (%.6f s; "
                           "it started at %.6f s)",
                           kSteppedWho, rec.t_s.back(), static_cast<double>(t0 + total) / rate,
                           static_cast<double>(t0) / rate));

  Frf out;
  out.method = "stepped_sine";
  out.line_spacing_Hz = program.step_Hz;
  out.device_time_s = static_cast<double>(total) / rate;
  out.lines.reserve(lines.size());
  for (std::size_t j = 0; j < lines.size(); ++j) {
    const LineTicks& l = lines[j];
    const double f_Hz = l.increment * rate / kTurn;
    const std::vector<std::size_t> idx =
        samples_in(r.tick, t0 + l.measure_begin, t0 + l.end);
    const std::size_t needed = std::max<std::size_t>(8, 4 * std::size_t{l.measure_cycles});
    if (idx.size() < needed)
      throw DataError(strf("%s: line %zu (%.4f Hz) has %zu samples in its %u measured cycles; "
                             "it needs %zu (a faster stream or more cycles)",
                             kSteppedWho, j, f_Hz, idx.size(), l.measure_cycles, needed));
    const SineFit fi = fit_sine(rec.i_A, 1.0, idx, r.tick, t0 + l.begin, l.increment,
                                control_rate_Hz, true);
    const SineFit fz = fit_sine(rec.z_mm, 1e-3, idx, r.tick, t0 + l.begin, l.increment,
                                control_rate_Hz, true);
    FrfLine line;
    line.f_Hz = f_Hz;
    line.z_mean_m = fz.mean;
    const double kf = detail::force_constant_at(options, line.z_mean_m);
    line.F_N = kf * fi.X;
    line.Z_m = fz.X;
    line.G_m_per_N = line.Z_m / line.F_N;
    const double sF = kf * fi.sigma;
    line.sigma_m_per_N =
        std::sqrt(fz.sigma * fz.sigma + std::norm(line.G_m_per_N) * sF * sF) / std::abs(line.F_N);
    out.lines.push_back(line);
  }
  return out;
}

}  // namespace palp::analysis
