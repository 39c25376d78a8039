// SPDX-License-Identifier: Apache-2.0
// ADC transfer functions of the pressure sensors and the current-sense chain.
#include "palp/plant/sensors.hpp"

#include <algorithm>
#include <cmath>

namespace palp::plant {
namespace {

// 2^bits, exactly (bits <= 16): scaling by it is exact, as std::ldexp is, without the call.
double two_to(int bits) { return static_cast<double>(1u << bits); }

// std::clamp(std::nearbyint(scaled), 0, top) without the library call: below 0 (or -0.5) the
// clamp gives 0 either way; for 0 <= x < 2^52 adding and taking away 2^52 rounds x to an integer
// in the current rounding mode, exactly as nearbyint does; at 2^52 and above (and for +inf) the
// clamp gives top either way. NaN stays NaN, as before.
std::uint16_t to_code(double scaled, int bits) {
  constexpr double kTwo52 = 4503599627370496.0;
  const double top = two_to(bits) - 1.0;
  double r = scaled;
  if (scaled >= 0.0 && scaled < kTwo52) r = (scaled + kTwo52) - kTwo52;
  const double c = std::clamp(r, 0.0, top);
  return static_cast<std::uint16_t>(c);
}

}  // namespace

std::uint16_t pressure_code_from_Pa(double pressure_Pa, double full_scale_Pa, int bits) {
  return to_code((0.5 + 0.4 * pressure_Pa / full_scale_Pa) * two_to(bits), bits);
}

double pressure_Pa_from_code(std::uint16_t code, double full_scale_Pa, int bits) {
  return (std::ldexp(static_cast<double>(code), -bits) - 0.5) / 0.4 * full_scale_Pa;
}

std::uint16_t current_code_from_A(double current_A, double full_scale_A, int bits) {
  const double half = two_to(bits - 1);
  return to_code(half + current_A / full_scale_A * half, bits);
}

double current_A_from_code(std::uint16_t code, double full_scale_A, int bits) {
  const double half = two_to(bits - 1);
  return (static_cast<double>(code) - half) / half * full_scale_A;
}

}  // namespace palp::plant
