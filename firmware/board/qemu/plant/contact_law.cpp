// SPDX-License-Identifier: Apache-2.0
// The scene's elastic contact law: Sneddon sphere from a compile-time table, bottom effect.
#include "contact_law.hpp"

#include <array>

namespace palp::qemu {
namespace {

using C = ContactConstants;

// ---- the exact Sneddon sphere, in double, at compile time only -----------------------------
// (double here costs nothing on the target: the table is computed by the compiler and stored
// as float; the runtime path below is float throughout.)

constexpr double kLn2 = 0.693147180559945309417;

// ln(y) for y > 0: y = m 2^e with m in [1/sqrt 2, sqrt 2], ln m = 2 atanh((m - 1) / (m + 1)) by
// its series (|z| <= 0.172, so each term is 34 times smaller than the last).
constexpr double log_cx(double y) {
  int e = 0;
  while (y > 1.4142135623730951) {
    y *= 0.5;
    ++e;
  }
  while (y < 0.7071067811865476) {
    y *= 2.0;
    --e;
  }
  const double z = (y - 1.0) / (y + 1.0), z2 = z * z;
  double term = z, sum = 0.0;
  for (int k = 1; k < 60; k += 2) {
    sum += term / k;
    term *= z2;
  }
  return e * kLn2 + 2.0 * sum;
}

constexpr double atanh_cx(double u) { return 0.5 * log_cx((1.0 + u) / (1.0 - u)); }

constexpr double sqrt_cx(double x) {  // Newton from above, x > 0
  double r = x > 1.0 ? x : 1.0;
  for (int k = 0; k < 200; ++k) {
    const double next = 0.5 * (r + x / r);
    if (!(next < r)) break;
    r = next;
  }
  return r;
}

// u = a / R at depth d = delta / R: the root of u atanh(u) = d in (0, 1), by bisection (the left
// side increases from 0 to infinity), 64 halvings: to the last bit of a double.
constexpr double contact_radius_cx(double d) {
  double lo = 0.0, hi = 1.0;
  for (int k = 0; k < 64; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (mid * atanh_cx(mid) < d ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

struct Node {
  float g;  // u / sqrt(d)      (-> 1 at d = 0)
  float h;  // S / d^1.5, S = (1 + u^2) atanh(u) - u   (-> 4/3 at d = 0)
};

constexpr int kNodes = C::kTableCells + 1;

constexpr std::array<Node, kNodes> make_table() {
  std::array<Node, kNodes> t{};
  t[0] = {1.0f, static_cast<float>(4.0 / 3.0)};
  for (int k = 1; k < kNodes; ++k) {
    const double d = static_cast<double>(C::kTableMaxDepth) * k / C::kTableCells;
    const double u = contact_radius_cx(d);
    const double s = (1.0 + u * u) * atanh_cx(u) - u;  // >= 0.125 u: cancellation < 1e-14
    const double sd = sqrt_cx(d);
    t[static_cast<std::size_t>(k)] = {static_cast<float>(u / sd), static_cast<float>(s / (d * sd))};
  }
  return t;
}

constexpr std::array<Node, kNodes> kSneddon = make_table();

// ---- runtime, float ---------------------------------------------------------------------

constexpr float kCellsPerUnitDepth = C::kTableCells / C::kTableMaxDepth;
constexpr float kInvRadius = 1.0f / C::kTipRadius_m;
constexpr float kForceScale_N = C::kEStar_Pa * C::kTipRadius_m * C::kTipRadius_m;  // E* R^2
constexpr float kStiffnessScale = 2.0f * C::kEStar_Pa * C::kTipRadius_m;           // 2 E* R
constexpr float kChiPerRootD = C::kTipRadius_m / C::kLayerThickness_m;  // chi = R sqrt(d) / h
// d(chi)/d(delta) = 1 / (2 h sqrt(d)): F_sphere phi' dchi/ddelta = E* R^2 H(d) d phi' / (2 h)
constexpr float kSlopeScale = kForceScale_N / (2.0f * C::kLayerThickness_m);

}  // namespace

ContactPoint contact_elastic(float depth_m) {
  if (!(depth_m > 0.0f)) return {};
  float d = depth_m * kInvRadius;
  if (d > C::kTableMaxDepth) d = C::kTableMaxDepth;

  // 4-point Lagrange cubic through nodes j..j+3 around the cell of d (the end cells use the
  // nearest four), at s = position in node units from node j.
  const float c = d * kCellsPerUnitDepth;
  int j = static_cast<int>(c) - 1;
  if (j < 0) j = 0;
  if (j > C::kTableCells - 3) j = C::kTableCells - 3;
  const float s = c - static_cast<float>(j);
  const float s1 = s - 1.0f, s2 = s - 2.0f, s3 = s - 3.0f;
  const float w0 = -s1 * s2 * s3 * (1.0f / 6.0f);
  const float w1 = s * s2 * s3 * 0.5f;
  const float w2 = -s * s1 * s3 * 0.5f;
  const float w3 = s * s1 * s2 * (1.0f / 6.0f);
  const Node* n = &kSneddon[static_cast<std::size_t>(j)];
  const float g = w0 * n[0].g + w1 * n[1].g + w2 * n[2].g + w3 * n[3].g;
  const float h = w0 * n[0].h + w1 * n[1].h + w2 * n[2].h + w3 * n[3].h;

  const float root_d = __builtin_sqrtf(d);
  const float sphere_force = kForceScale_N * h * d * root_d;    // E* R^2 S
  const float sphere_stiffness = kStiffnessScale * g * root_d;  // 2 E* a

  // Dimitriadis et al. (2002) bonded layer, nu = 0.5 (hil/plant contact_laws.cpp, same numbers).
  const float chi = kChiPerRootD * root_d;
  const float phi = 1.0f + chi * (1.133f + chi * (1.283f + chi * (0.769f + chi * 0.0975f)));
  const float phi_slope = 1.133f + chi * (2.566f + chi * (2.307f + chi * 0.39f));
  return {sphere_force * phi, sphere_stiffness * phi + kSlopeScale * h * d * phi_slope};
}

}  // namespace palp::qemu
