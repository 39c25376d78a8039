// SPDX-License-Identifier: Apache-2.0
// The Sneddon sphere from a table (contact.hpp, README.md "Speed and sameness").
//
// In d = delta / R the law is F = E* R^2 S(d) and dF/d(delta) = 2 E* R u(d), u = a / R solving
// u atanh(u) = d and S = (1 + u^2) atanh(u) - u. Near d = 0, u^2 / d and S / d^1.5 are analytic
// in d (u atanh u = u^2 + u^4 / 3 + ..., S = 4/3 u^3 + 8/15 u^5 + ...), so the table holds the
// smooth factors g(d) = u / sqrt(d) and h(d) = S / d^1.5, and the law's relative error is theirs
// (no loss near the first touch, where F -> 0). Each of kCells cells of width 1 / kCellsPerUnit
// over [0, kSneddonTableMaxDepth] carries the cubic through the four nearest nodes (one-sided in
// the end cells) in its local coordinate t in [0, 1). The nodes are the exact law: u by Newton
// (sneddon_contact_radius, 1e-13) and S by its series below u = 1/2 (no cancellation).
#include <array>
#include <cmath>
#include <cstddef>

#include "palp/plant/contact.hpp"

namespace palp::plant {
namespace {

constexpr int kCellsPerUnit = 128;
constexpr int kCells = static_cast<int>(kSneddonTableMaxDepth) * kCellsPerUnit;  // 512

// S(u) = sum_{m >= 1} 4m / (4m^2 - 1) u^(2m + 1) below u = 1/2 (terms fall by u^2 <= 1/4)
double shape_of(double u) {
  if (u >= 0.5) return (1.0 + u * u) * std::atanh(u) - u;
  const double u2 = u * u;
  double term = u * u2, sum = 0.0;
  for (int m = 1; m < 40; ++m, term *= u2) sum += 4.0 * m / (4.0 * m * m - 1.0) * term;
  return sum;
}

struct Factors {
  double g, h;
};
Factors factors_at(double d) {
  if (d == 0.0) return {1.0, 4.0 / 3.0};
  const double u = sneddon_contact_radius(1.0, d);
  const double s = std::sqrt(d);
  return {u / s, shape_of(u) / (d * s)};
}

// g and h over a cell as c0 + t (c1 + t (c2 + t c3))
struct Cell {
  std::array<double, 4> g, h;
};

// the cubic through (t_k, y_k), t_k = first + k, in powers of t
std::array<double, 4> cubic_through(int first, const std::array<double, 4>& y) {
  std::array<double, 4> c{};
  for (int a = 0; a < 4; ++a) {
    // Lagrange basis polynomial of node a, expanded: prod_{b != a} (t - t_b) / (t_a - t_b)
    std::array<double, 4> p{1.0, 0.0, 0.0, 0.0};
    double denominator = 1.0;
    for (int b = 0; b < 4; ++b) {
      if (b == a) continue;
      const double tb = first + b;
      for (int k = 3; k > 0; --k) p[static_cast<std::size_t>(k)] = p[static_cast<std::size_t>(k - 1)] - tb * p[static_cast<std::size_t>(k)];
      p[0] = -tb * p[0];
      denominator *= static_cast<double>(a - b);
    }
    for (std::size_t k = 0; k < 4; ++k) c[k] += y[static_cast<std::size_t>(a)] * p[k] / denominator;
  }
  return c;
}

const std::array<Cell, kCells> kTable = [] {
  std::array<Factors, kCells + 1> node{};
  for (int i = 0; i <= kCells; ++i) node[static_cast<std::size_t>(i)] = factors_at(static_cast<double>(i) / kCellsPerUnit);
  std::array<Cell, kCells> table{};
  for (int i = 0; i < kCells; ++i) {
    const int j = i == 0 ? 0 : (i == kCells - 1 ? kCells - 3 : i - 1);  // stencil's first node
    std::array<double, 4> g{}, h{};
    for (int k = 0; k < 4; ++k) {
      g[static_cast<std::size_t>(k)] = node[static_cast<std::size_t>(j + k)].g;
      h[static_cast<std::size_t>(k)] = node[static_cast<std::size_t>(j + k)].h;
    }
    table[static_cast<std::size_t>(i)] = {cubic_through(j - i, g), cubic_through(j - i, h)};
  }
  return table;
}();

double horner(const std::array<double, 4>& c, double t) { return c[0] + t * (c[1] + t * (c[2] + t * c[3])); }

}  // namespace

ElasticPoint sneddon_sphere_tabulated(double e_star_Pa, double radius_m, double depth_m) {
  if (!(depth_m > 0.0)) return {};
  const double d = depth_m / radius_m;
  if (!(d < kSneddonTableMaxDepth)) return sneddon_sphere(e_star_Pa, radius_m, depth_m);
  const double x = d * kCellsPerUnit;
  const int i = static_cast<int>(x);
  const double t = x - i;
  const Cell& cell = kTable[static_cast<std::size_t>(i)];
  const double s = std::sqrt(d);
  const double u = horner(cell.g, t) * s;
  const double shape = horner(cell.h, t) * d * s;
  return {e_star_Pa * radius_m * radius_m * shape, 2.0 * e_star_Pa * radius_m * u};
}

}  // namespace palp::plant
