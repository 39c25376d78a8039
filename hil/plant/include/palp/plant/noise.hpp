// Counter-based Gaussian noise: the sample for (seed, stream, tick) is a pure function of those
// three numbers, so a run repeats exactly for a given seed whatever the order or number of sensor
// reads, and one sensor's reads never shift another's noise.
#pragma once

#include <cstdint>

namespace palp::plant {

/// Independent noise streams, one per sensor.
enum class NoiseStream : std::uint32_t {
  current_sense = 1,
  encoder = 2,
  pressure_base = 16,  // + channel number 1..6
};

/// The hash of (seed, stream) that every sample of that stream starts from: a plant keeps its
/// streams' keys instead of hashing seed and stream again every tick.
std::uint64_t noise_key(std::uint64_t seed, std::uint32_t stream);

/// Standard normal deviate N(0, 1) of the stream with this key at this tick (splitmix64 hashing
/// and Box-Muller). gaussian_at(noise_key(seed, stream), tick) == gaussian(seed, stream, tick).
double gaussian_at(std::uint64_t key, std::uint64_t tick);

/// Bounds lo <= gaussian_at(key, tick) <= hi, for much less work: ln and cos by short
/// polynomials with proven error bounds (README.md "Noise"); hi - lo is about 2e-5 |g|.
struct GaussianBracket {
  double lo, hi;
};
GaussianBracket gaussian_bracket(std::uint64_t key, std::uint64_t tick);

/// What a quantised reading of a noisy signal is: code_of(g) for g = gaussian_at(key, tick)
/// (bracket = gaussian_bracket(key, tick)), where code_of is non-decreasing in g (a sensor's
/// transfer: adding sigma g, sigma >= 0, then scaling by positive numbers and rounding, each
/// step monotonic in floating point too). The
/// bracket's ends usually give the same code, which is then code_of's exact answer; only when a
/// code boundary falls inside the bracket is gaussian_at itself computed.
template <class CodeOf>
auto quantised_noise(const GaussianBracket& bracket, std::uint64_t key, std::uint64_t tick,
                     CodeOf&& code_of) {
  const auto lo = code_of(bracket.lo);
  if (lo == code_of(bracket.hi)) return lo;
  return code_of(gaussian_at(key, tick));
}
/// The same with the bracket taken here (a caller of many streams takes theirs first, so that
/// the CPU overlaps their independent work).
template <class CodeOf>
auto quantised_noise(std::uint64_t key, std::uint64_t tick, CodeOf&& code_of) {
  return quantised_noise(gaussian_bracket(key, tick), key, tick, code_of);
}

/// Standard normal deviate N(0, 1) for (seed, stream, tick).
inline double gaussian(std::uint64_t seed, std::uint32_t stream, std::uint64_t tick) {
  return gaussian_at(noise_key(seed, stream), tick);
}

}  // namespace palp::plant
