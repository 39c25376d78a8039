// SPDX-License-Identifier: Apache-2.0
// The multisine generator (multisine_synth.hpp).
#include "palp/fw/multisine_synth.hpp"

#include "palp/fw/waveform.hpp"
#include "palp/protocol/multisine.hpp"

namespace palp::fw {
namespace {
constexpr double kTwoPi = 6.28318530717958647692;
constexpr double kPi = 3.14159265358979323846;
constexpr double kFloatUnit = 1.0 / 16777216.0;  // 2^-24, float unit roundoff
constexpr double kPhaseUnit = 1.0 / 4294967296.0;  // 2^-32 turn
}  // namespace

double multisine_error_bound(const MultisineLines& lines, std::uint32_t rate_Hz) {
  const double sub_period_s = static_cast<double>(lines.ticks_per_point) / rate_Hz;
  const double fundamental_Hz = static_cast<double>(rate_Hz) / lines.period_ticks;
  const double K = lines.count;
  double bound = 0.0;
  for (std::uint32_t n = 0; n < lines.count; ++n) {
    const double h = static_cast<double>(lines.first) + static_cast<double>(n) * lines.step;
    const double w = kTwoPi * h * fundamental_Hz * sub_period_s;  // radians per sub-rate step
    bound += w * w / 8.0;                                         // interpolation
    bound += static_cast<double>(kSineMaxError);                  // table
    bound += kTwoPi * (h + 1.0) * kPhaseUnit;                     // phase quantisation
  }
  bound += (K - 1.0) * K * kFloatUnit;  // summing K terms of magnitude <= 1
  bound += 6.0 * K * kFloatUnit;        // the interpolation's own rounding
  return bound;
}

namespace {
// sin(y) by its series, for |y| <= pi/2 (exact to 1e-12 there; load- and test-time only)
double sin_series(double y) {
  const double y2 = y * y;
  return y * (1.0 - y2 / 6.0 * (1.0 - y2 / 20.0 * (1.0 - y2 / 42.0 * (1.0 - y2 / 72.0 *
             (1.0 - y2 / 110.0 * (1.0 - y2 / 156.0))))));
}
}  // namespace

double multisine_amplitude_error(double frequency_Hz, std::uint32_t ticks_per_point) {
  // tick-by-tick linear interpolation between points D ticks apart is a triangular filter of
  // D^2 taps: gain (sin(pi f Ts) / (D sin(pi f Ts / D)))^2 at f, Ts = D ticks
  const double y = kPi * frequency_Hz / kMultisineSubRate_Hz;
  const double gain = sin_series(y) / (ticks_per_point * sin_series(y / ticks_per_point));
  return 1.0 - gain * gain;
}

void MultisineSynth::configure(const MultisineLines& lines) {
  auto clamp = [](std::uint32_t v, std::uint32_t lo, std::uint32_t hi) {
    return v < lo ? lo : (v > hi ? hi : v);
  };
  count_ = clamp(lines.count, 1, kMaxMultisineLines);
  first_ = lines.first;
  step_ = lines.step;
  period_ = clamp(lines.period_ticks, 1, 0xFFFFFFFFu);
  per_point_ = clamp(lines.ticks_per_point, 1, kMaxTicksPerPoint);
  // phases in line order, bit for bit those of multisine_phase_turns() (multisine.hpp), without
  // its per-line loops and 64-bit divisions
  std::uint32_t x = lines.phase_seed == 0 ? 1u : lines.phase_seed;  // random_seeded
  // schroeder: p_n = floor(((2K - r_n) mod 2K) 2^32 / 2K), r_n = n (n + 1) mod 2K, with
  // floor(v 2^32 / m) = v q + floor(v rem / m) for 2^32 = q m + rem (v rem < m^2 fits 32 bits)
  const std::uint32_t m = 2 * count_;
  const std::uint32_t q = 0xFFFFFFFFu / m + (0xFFFFFFFFu % m + 1 == m ? 1 : 0);
  const auto rem = static_cast<std::uint32_t>((1ull << 32) - static_cast<std::uint64_t>(q) * m);
  std::uint32_t r = 0;
  for (std::uint32_t n = 0; n < count_; ++n) {
    std::uint32_t phi = 0;
    switch (lines.phase_mode) {
      case proto::PhaseMode::random_seeded:
        x = proto::xorshift32(x);
        phi = x;
        break;
      case proto::PhaseMode::schroeder: {
        if (n > 0) {
          r += 2 * n;  // n (n + 1) - (n - 1) n
          if (r >= m) r -= m;
        }
        const std::uint32_t v = r == 0 ? 0 : m - r;
        phi = v * q + v * rem / m;
        break;
      }
      default:
        break;
    }
    phase_[n] = phi + kQuarterTurn;  // cos(a) = sin(a + 1/4 turn)
  }
  for (std::uint32_t s = 0; s <= per_point_; ++s)
    slice_[s] = static_cast<std::uint16_t>(s * count_ / per_point_);
  const std::uint64_t step_turns = static_cast<std::uint64_t>(per_point_) << 32;
  theta_step_ = static_cast<std::uint32_t>(step_turns / period_);
  theta_step_rem_ = static_cast<std::uint32_t>(step_turns % period_);
  inv_per_point_ = 1.0f / static_cast<float>(per_point_);

  Theta th{};  // point 0: t = 0
  primed0_ = point_sum(th);
  advance(th);
  primed1_ = point_sum(th);
  advance(th);
  primed_theta_ = th;
  rewind();
}

void MultisineSynth::rewind() {
  x_prev_ = primed0_;
  x_next_ = primed1_;
  x_acc_ = 0.0f;
  theta_ = primed_theta_;
  sub_ = 0;
  lines_last_step_ = 0;
}

std::uint32_t MultisineSynth::max_lines_per_step() const {
  return (count_ + per_point_ - 1) / per_point_;
}

void MultisineSynth::advance(Theta& th) const {
  th.remainder += theta_step_rem_;
  if (th.remainder >= period_) {
    th.remainder -= period_;
    ++th.turns;
  }
  th.turns += theta_step_;
}

float MultisineSynth::sum_lines(const Theta& th, std::uint32_t lo, std::uint32_t hi) const {
  const std::uint32_t dh = step_ * th.turns;  // phase step between neighbouring lines
  std::uint32_t h = (first_ + lo * step_) * th.turns;
  float sum = 0.0f;
  for (std::uint32_t n = lo; n < hi; ++n) {
    sum += sin_turns(phase_[n] + h);
    h += dh;
  }
  return sum;
}

float MultisineSynth::point_sum(const Theta& th) const {
  float sum = 0.0f;  // slice by slice, as step() does, so every period rounds alike
  for (std::uint32_t s = 0; s < per_point_; ++s) sum += sum_lines(th, slice_[s], slice_[s + 1]);
  return sum;
}

float MultisineSynth::step() {
  const float x = x_prev_ + (x_next_ - x_prev_) * (static_cast<float>(sub_) * inv_per_point_);
  const std::uint32_t lo = slice_[sub_], hi = slice_[sub_ + 1];
  x_acc_ += sum_lines(theta_, lo, hi);
  lines_last_step_ = hi - lo;
  if (++sub_ == per_point_) {
    sub_ = 0;
    x_prev_ = x_next_;
    x_next_ = x_acc_;
    x_acc_ = 0.0f;
    advance(theta_);
  }
  return x;
}

}  // namespace palp::fw
