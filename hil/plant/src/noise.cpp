// SPDX-License-Identifier: Apache-2.0
// Counter-based Gaussian noise: a splitmix64 hash of (stream key, tick) through a 256-layer
// ziggurat (README.md "Noise").
#include "palp/plant/noise.hpp"

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

// Salts that derive further independent words from a draw's word, for the rare draws that need
// more than one (the wedges, the tail and a rejected point).
constexpr std::uint64_t kWedgeSalt = 0xD1B54A32D192ED03ull;
constexpr std::uint64_t kTailSalt = 0x8CB92BA72F3D8DD7ull;
constexpr std::uint64_t kRetrySalt = 0xA0761D6478BD642Full;

double density(double x) { return std::exp(-0.5 * x * x); }  // unnormalised

// The ziggurat of the half-normal density f(x) = exp(-x^2 / 2) (Marsaglia and Tsang 2000): 256
// layers of equal area v. Layer 0 is the base strip, of width x[0] = v / f(r) and height f(r):
// the rectangle [0, r] x [0, f(r)] plus, beyond r, the tail (the two have area v together).
// Layer k >= 1 is the rectangle of width x[k] between the heights f(x[k]) and f(x[k + 1]), with
// x[1] = r > x[2] > ... > x[256] = 0. r is found by bisection so that the layers stack exactly
// to f(0) = 1 (r = 3.6541528853610088 for 256 layers).
constexpr int kLayers = 256;
struct Ziggurat {
  std::array<double, kLayers + 1> x{};      // edges, above
  std::array<double, kLayers + 1> f{};      // f(x[k])
  std::array<double, kLayers> scale{};      // x[k] 2^-53: a 53-bit integer times it is u x[k]
  double r = 0.0;
};

// f(x[255]) + v / x[255] - 1 for a trial r: positive when the layers overshoot 1 (r too small);
// the edges x[0 .. 255] into `edges` when given
double stack_excess(double r, std::array<double, kLayers + 1>* edges) {
  const double v = r * density(r) + std::sqrt(std::numbers::pi / 2.0) * std::erfc(r / std::numbers::sqrt2);
  double x = r;
  if (edges) {
    (*edges)[0] = v / density(r);
    (*edges)[1] = r;
  }
  for (int k = 1; k < kLayers - 1; ++k) {
    const double top = density(x) + v / x;
    if (!(top < 1.0)) return 1.0;  // the stack reached the peak before its last layer
    x = std::sqrt(-2.0 * std::log(top));
    if (edges) (*edges)[static_cast<std::size_t>(k + 1)] = x;
  }
  return density(x) + v / x - 1.0;
}

const Ziggurat kZig = [] {
  double lo = 3.0, hi = 4.5;  // stack_excess(3) > 0 > stack_excess(4.5)
  for (int k = 0; k < 200 && lo < hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (stack_excess(mid, nullptr) > 0.0 ? lo : hi) = mid;
  }
  std::array<double, kLayers + 1> edges{};
  stack_excess(hi, &edges);
  edges[kLayers] = 0.0;
  Ziggurat z;
  z.r = hi;
  z.x = edges;
  for (int k = 0; k <= kLayers; ++k) z.f[static_cast<std::size_t>(k)] = density(z.x[static_cast<std::size_t>(k)]);
  for (int k = 0; k < kLayers; ++k)
    z.scale[static_cast<std::size_t>(k)] = z.x[static_cast<std::size_t>(k)] * 0x1.0p-53;
  return z;
}();

// A half-normal deviate beyond r (Marsaglia 1964): a = -ln(u1) / r, b = -ln(u2), accepted when
// 2 b > a^2; the words come from the draw's word, one pair per attempt.
double tail_beyond_r(std::uint64_t word) {
  for (;;) {
    const std::uint64_t w1 = mix(word ^ kTailSalt);
    const std::uint64_t w2 = mix(w1 ^ kTailSalt);
    const double a = -std::log(unit(w1)) / kZig.r;
    const double b = -std::log(unit(w2));
    if (b + b > a * a) return kZig.r + a;
    word = w2;
  }
}

// The draws outside a layer's core (1.5 %): the wedge test against f or the tail, with words
// derived from this one, and a new word when the point is rejected. Out of line, so that the
// common path needs no registers saved.
[[gnu::noinline]] double gaussian_outside_core(std::uint64_t word) {
  for (;;) {
    const auto k = static_cast<std::size_t>(word & 0xFFu);
    const double sign = (word & 0x100u) ? -1.0 : 1.0;
    const double z = static_cast<double>(word >> 11) * kZig.scale[k];
    if (z < kZig.x[k + 1]) return sign * z;
    if (k == 0) return sign * tail_beyond_r(word);
    const double y = kZig.f[k] + (unit(mix(word ^ kWedgeSalt)) - 0x1.0p-53) * (kZig.f[k + 1] - kZig.f[k]);
    if (y < density(z)) return sign * z;
    word = mix(word ^ kRetrySalt);
  }
}

}  // namespace

std::uint64_t noise_key(std::uint64_t seed, std::uint32_t stream) {
  return mix(mix(seed) ^ (static_cast<std::uint64_t>(stream) << 32));
}

double ziggurat_tail_start() { return kZig.r; }

// One 64-bit word per draw: bits 0-7 pick the layer, bit 8 the sign, bits 11-63 the uniform
// position u in [0, 1) along the layer (disjoint bits, so the three are independent). Inside
// the layer's core (u x[k] < x[k + 1]; 98.5 % of draws) the deviate is u x[k], one multiply,
// its sign bit set from bit 8 (no branch on a coin flip).
double gaussian_at(std::uint64_t key, std::uint64_t tick) {
  const std::uint64_t word = mix(key ^ tick);
  const auto k = static_cast<std::size_t>(word & 0xFFu);
  const double z = static_cast<double>(word >> 11) * kZig.scale[k];
  if (z < kZig.x[k + 1]) return std::bit_cast<double>(std::bit_cast<std::uint64_t>(z) ^ ((word & 0x100u) << 55));
  return gaussian_outside_core(word);
}

}  // namespace palp::plant
