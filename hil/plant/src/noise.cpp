// Counter-based Gaussian noise (splitmix64 hash of seed, stream and tick; Box-Muller).
#include "palp/plant/noise.hpp"

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

double gaussian(std::uint64_t seed, std::uint32_t stream, std::uint64_t tick) {
  const std::uint64_t key = mix(mix(seed) ^ (static_cast<std::uint64_t>(stream) << 32));
  const std::uint64_t a = mix(key ^ tick);
  const std::uint64_t b = mix(a ^ 0xD1B54A32D192ED03ull);
  return std::sqrt(-2.0 * std::log(unit(a))) * std::cos(2.0 * std::numbers::pi * unit(b));
}

}  // namespace palp::plant
