// Counter-based Gaussian noise (splitmix64 hash of seed, stream and tick; Box-Muller).
#include "palp/plant/noise.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numbers>

namespace palp::plant {
namespace {

std::uint64_t mix(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Uniform in (0, 1]: 53 random bits, never zero (log stays finite).
double unit(std::uint64_t bits) { return (static_cast<double>(bits >> 11) + 1.0) * 0x1.0p-53; }

}  // namespace

std::uint64_t noise_key(std::uint64_t seed, std::uint32_t stream) {
  return mix(mix(seed) ^ (static_cast<std::uint64_t>(stream) << 32));
}

double gaussian_at(std::uint64_t key, std::uint64_t tick) {
  const std::uint64_t a = mix(key ^ tick);
  const std::uint64_t b = mix(a ^ 0xD1B54A32D192ED03ull);
  return std::sqrt(-2.0 * std::log(unit(a))) * std::cos(2.0 * std::numbers::pi * unit(b));
}

namespace {

// cos x = sum_k (-1)^k x^2k / (2k)!, k = 0..5: for |x| <= pi/2 the first term left out,
// x^12 / 12!, is below 5e-7.
constexpr std::array<double, 6> kCos = [] {
  std::array<double, 6> c{};
  double f = 1.0;
  for (int k = 0; k < 6; ++k) {
    c[static_cast<std::size_t>(k)] = (k % 2 == 0 ? 1.0 : -1.0) / f;
    f *= (2 * k + 1) * (2 * k + 2);
  }
  return c;
}();

// cos(2 pi t) for t in [0, 1] within 5e-7 + a few 1e-16, without branches: z = |t - round(t)|
// in [0, 1/2], folded to w = min(z, 1/2 - z) in [0, 1/4] (cos(2 pi z) = -cos(2 pi (1/2 - z))),
// x = 2 pi w in [0, pi/2], the series in Estrin's scheme (a short dependency chain).
double cos_turns(double t) {
  const double z = std::fabs(t - static_cast<double>(static_cast<int>(t + 0.5)));
  const double w = std::min(z, 0.5 - z);
  const double x = 2.0 * std::numbers::pi * w;
  const double x2 = x * x, x4 = x2 * x2;
  const auto& c = kCos;
  const double v = (c[0] + c[1] * x2) + x4 * ((c[2] + c[3] * x2) + x4 * (c[4] + c[5] * x2));
  return z > 0.25 ? -v : v;
}

// ln u for u in (0, 1] within 2e-13 + a few 1e-16 per unit of |ln u|: u = 2^e f with f in
// [1, 2); f's top 7 fraction bits pick c = 1 + (i + 1/2) / 128, and ln f = ln c + ln(1 + r) with
// r = f / c - 1, |r| < 1/256, by its series to r^4 (the first term left out, r^5 / 5, is below
// 2e-13). The table holds 1/c and the library's ln c.
struct LogEntry {
  double inv_c, ln_c;
};
const std::array<LogEntry, 128> kLogTable = [] {
  std::array<LogEntry, 128> t{};
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double c = 1.0 + (static_cast<double>(i) + 0.5) / 128.0;
    t[i] = {1.0 / c, std::log(c)};
  }
  return t;
}();

double log_unit(double u) {
  const auto bits = std::bit_cast<std::uint64_t>(u);
  const int e = static_cast<int>(bits >> 52) - 1023;  // u > 0: no sign bit; u >= 2^-53: normal
  const double f = std::bit_cast<double>((bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull);
  const LogEntry& entry = kLogTable[(bits >> 45) & 127u];
  const double r = f * entry.inv_c - 1.0;
  const double r2 = r * r;
  const double series = r - r2 * (0.5 - r * (1.0 / 3.0)) - r2 * r2 * 0.25;
  return e * std::numbers::ln2 + entry.ln_c + series;
}

// The bracket's error budget (the library's log and cos are within 1 ulp): ln u above within
// 2e-13 + 1e-14, so -2 ln u within 5e-13: taken as 5e-11; cos within 5e-7 + 3e-15: taken as 1e-5.
constexpr double kRadius2Error = 5e-11;
constexpr double kCosError = 1e-5;

}  // namespace

GaussianBracket gaussian_bracket(std::uint64_t key, std::uint64_t tick) {
  const std::uint64_t a = mix(key ^ tick);
  const std::uint64_t b = mix(a ^ 0xD1B54A32D192ED03ull);
  // gaussian_at is fl(fl(sqrt(-2 ln u)) fl(cos(2 pi t))): sqrt and the product round
  // monotonically, so bounds on -2 ln u and on the cosine bound it through the corners
  const double r2 = -2.0 * log_unit(unit(a));
  const double r_lo = std::sqrt(std::max(0.0, r2 - kRadius2Error));
  const double r_hi = std::sqrt(r2 + kRadius2Error);
  const double c = cos_turns(unit(b));
  const double c_lo = c - kCosError, c_hi = c + kCosError;
  return {std::min(r_lo * c_lo, r_hi * c_lo), std::max(r_lo * c_hi, r_hi * c_hi)};
}

}  // namespace palp::plant
