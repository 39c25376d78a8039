// SPDX-License-Identifier: Apache-2.0
// The sine table, computed by the compiler (no libm, no start-up cost).
#include "palp/fw/waveform.hpp"

#include <array>

namespace palp::fw {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Taylor series, for |x| <= pi/4: the first omitted term is below 1e-19.
constexpr double sin_small(double x) {
  double term = x, sum = x;
  for (int k = 1; k <= 10; ++k) {
    term *= -x * x / ((2.0 * k) * (2.0 * k + 1.0));
    sum += term;
  }
  return sum;
}
constexpr double cos_small(double x) {
  double term = 1.0, sum = 1.0;
  for (int k = 1; k <= 10; ++k) {
    term *= -x * x / ((2.0 * k - 1.0) * (2.0 * k));
    sum += term;
  }
  return sum;
}

// sin(2 pi k / N) from the octant symmetries, so every series argument stays within pi/4.
constexpr double sin_of_index(std::uint32_t k) {
  constexpr std::uint32_t N = kSineTableSize, quarter = N / 4, eighth = N / 8;
  const std::uint32_t q = (k % N) / quarter;  // quadrant
  const std::uint32_t r = (k % N) % quarter;  // index within it
  const double h = 2.0 * kPi / N;
  // s = sin(r h), c = cos(r h) for r h in [0, pi/2)
  const double s = r <= eighth ? sin_small(r * h) : cos_small((quarter - r) * h);
  const double c = r <= eighth ? cos_small(r * h) : sin_small((quarter - r) * h);
  switch (q) {
    case 0: return s;
    case 1: return c;
    case 2: return -s;
    default: return -c;
  }
}

constexpr std::array<detail::SineSample, kSineTableSize> make_sine_table() {
  std::array<detail::SineSample, kSineTableSize> t{};
  constexpr double kPerFraction = 1.0 / static_cast<double>(1u << detail::kFractionBits);
  for (std::uint32_t k = 0; k < kSineTableSize; ++k) {
    const double here = sin_of_index(k), next = sin_of_index(k + 1);
    t[k] = {static_cast<float>(here), static_cast<float>((next - here) * kPerFraction)};
  }
  return t;
}

constexpr std::array<detail::SineSample, kSineTableSize> kValues = make_sine_table();
static_assert(kValues[0].value == 0.0f && kValues[kSineTableSize / 4].value == 1.0f &&
              kValues[kSineTableSize / 2].value == 0.0f &&
              kValues[3 * kSineTableSize / 4].value == -1.0f);

}  // namespace

namespace detail {
constinit const std::array<SineSample, kSineTableSize> kSineTable = kValues;
}  // namespace detail

}  // namespace palp::fw
