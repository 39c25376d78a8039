// SPDX-License-Identifier: Apache-2.0
// Delta-method standard errors of delta0 and the tangent stiffnesses (indentation.hpp).
#include <algorithm>
#include <cmath>

#include "palp/analysis/indentation.hpp"

namespace palp::analysis {

const ModelFit* chosen_fit(const IndentationResult& r) {
  if (!r.chosen) return nullptr;
  switch (*r.chosen) {
    case Model::linear: return r.linear ? &*r.linear : nullptr;
    case Model::hertz: return r.hertz ? &*r.hertz : nullptr;
    case Model::sneddon: return r.sneddon ? &*r.sneddon : nullptr;
  }
  return nullptr;
}

DerivedSe derived_se(const IndentationResult& r) {
  DerivedSe d;
  const ModelFit* m = chosen_fit(r);
  if (m == nullptr || m->params.size() == 0 || m->se.size() == 0 || !std::isfinite(m->se[0])) {
    const std::string why = m != nullptr              ? "the fit gives no standard error"
                            : r.fit_reason.empty() ? "no model fitted"
                                                   : r.fit_reason;
    d.delta0_m = d.k_tangent_at_delta0_N_per_m = Value::absent(why);
    d.k_tangent_N_per_m.assign(r.k_tangent_N_per_m.size(), Value::absent(why));
    return d;
  }
  const double s = m->params[0], se_s = m->se[0];
  for (const auto& k : r.k_tangent_N_per_m)
    d.k_tangent_N_per_m.push_back(k ? Value::of(std::abs(*k.value * se_s / s)) : Value::absent(k.reason));
  if (!r.delta0_m) {
    d.delta0_m = d.k_tangent_at_delta0_N_per_m = Value::absent(r.delta0_m.reason);
    return d;
  }
  const double d0 = *r.delta0_m.value, kt = m->stiffness_N_per_m(d0);
  const double dd0_ds = -r.F0_N / (s * kt);
  const double h = std::max(1e-9, 1e-4 * d0);
  const double g2 = (m->stiffness_N_per_m(d0 + h) - m->stiffness_N_per_m(d0 - h)) / (2 * h * s);
  d.delta0_m = Value::of(std::abs(dd0_ds * se_s));
  d.k_tangent_at_delta0_N_per_m = Value::of(std::abs((kt / s + s * g2 * dd0_ds) * se_s));
  return d;
}

}  // namespace palp::analysis
