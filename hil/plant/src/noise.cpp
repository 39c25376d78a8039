// Counter-based Gaussian noise (splitmix64 hash of seed, stream and tick; Box-Muller).
#include "palp/plant/noise.hpp"

#include <algorithm>
#include <array>
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

// cos x = sum_k (-1)^k x^2k / (2k)!, k = 0..8: for |x| <= pi/2 the first term left out,
// x^18 / 18!, is below 5e-13.
constexpr std::array<double, 9> kCos = [] {
  std::array<double, 9> c{};
  double f = 1.0;
  for (int k = 0; k < 9; ++k) {
    c[static_cast<std::size_t>(k)] = (k % 2 == 0 ? 1.0 : -1.0) / f;
    f *= (2 * k + 1) * (2 * k + 2);
  }
  return c;
}();

// cos(2 pi t) for t in [0, 1], without branches: z = |t - round(t)| in [0, 1/2], folded to
// w = min(z, 1/2 - z) in [0, 1/4] (cos(2 pi z) = -cos(2 pi (1/2 - z))), x = 2 pi w in
// [0, pi/2], and the series evaluated in Estrin's scheme (a short dependency chain).
// Error < 5e-13 (truncation) + a few 1e-16 (rounding).
double cos_turns(double t) {
  const double z = std::fabs(t - static_cast<double>(static_cast<int>(t + 0.5)));
  const double w = std::min(z, 0.5 - z);
  const double x = 2.0 * std::numbers::pi * w;
  const double x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
  const auto& c = kCos;
  const double v = (c[0] + c[1] * x2) + x4 * (c[2] + c[3] * x2) +
                   x8 * ((c[4] + c[5] * x2) + x4 * (c[6] + c[7] * x2) + x8 * c[8]);
  return z > 0.25 ? -v : v;
}

}  // namespace

GaussianBracket gaussian_bracket(std::uint64_t key, std::uint64_t tick) {
  const std::uint64_t a = mix(key ^ tick);
  const std::uint64_t b = mix(a ^ 0xD1B54A32D192ED03ull);
  const double r = std::sqrt(-2.0 * std::log(unit(a)));  // bit for bit gaussian_at's radius
  // |cos_turns - cos(2 pi t)| < 6e-13 and the library's cos(fl(2 pi t)) is within 2e-15 of it;
  // the products round by < 1e-15 (|g| < 8.6): 1e-10 (1 + r) leaves a margin of over 100
  return {r * cos_turns(unit(b)), 1e-10 * (1.0 + r)};
}

}  // namespace palp::plant
