// SPDX-License-Identifier: Apache-2.0
// Per-repetition analysis and hysteresis: see palp/analysis/indentation.hpp.
#include <cmath>
#include <vector>

#include "palp/analysis/indentation.hpp"
#include "palp/error.hpp"

namespace palp::analysis {

namespace {

// Contiguous runs of equal rep values (the whole curve when rep is empty).
std::vector<Curve> split(const Curve& c) {
  std::vector<Curve> out;
  const Eigen::Index n = c.z_m.size();
  Eigen::Index b = 0;
  for (Eigen::Index k = 1; k <= n; ++k) {
    if (k == n || (c.rep.size() != 0 && c.rep[k] != c.rep[b])) {
      Curve one{c.z_m.segment(b, k - b), c.i_A.segment(b, k - b), {},
                c.i_cmd_A.size() != 0 ? Eigen::VectorXd(c.i_cmd_A.segment(b, k - b)) : Eigen::VectorXd()};
      out.push_back(std::move(one));
      b = k;
    }
  }
  return out;
}

RepetitionSummary::Stat stat(const std::vector<Value>& v) {
  const MeanSd m = mean_sd(v);
  return {m.mean, m.sd, m.n};
}

}  // namespace

std::vector<Hysteresis> hysteresis(const Curve& c, const IndentationParams& p, double contact_z_m) {
  validate(c, p);
  std::vector<Hysteresis> out;
  for (const Curve& one : split(c)) {
    const Branches b = loading_branch(one);
    if (b.unloading.empty() || b.loading.size() < 2) {
      out.push_back({Value::absent("the repetition has no unloading branch"),
                     Value::absent("the repetition has no unloading branch")});
      continue;
    }
    const Eigen::VectorXd F = coil_force_N(one, p);
    const Eigen::VectorXd Fo = object_force_N(one, p, contact_z_m);
    double loop = 0.0, work = 0.0;
    for (Eigen::Index k = 1; k < one.z_m.size(); ++k) {
      loop += 0.5 * (F[k] + F[k - 1]) * (one.z_m[k] - one.z_m[k - 1]);
    }
    for (size_t k = 1; k < b.loading.size(); ++k) {
      const int i = b.loading[k], j = b.loading[k - 1];
      work += 0.5 * (Fo[i] + Fo[j]) * (one.z_m[i] - one.z_m[j]);
    }
    // Close the loop from the last sample back to the first (a cycle that does not return
    // exactly to its start).
    const Eigen::Index last = one.z_m.size() - 1;
    loop += 0.5 * (F[0] + F[last]) * (one.z_m[0] - one.z_m[last]);
    Hysteresis h{Value::of(loop), work > 0.0 ? Value::of(loop / work)
                                             : Value::absent("no positive loading work")};
    out.push_back(h);
  }
  return out;
}

RepetitionSummary analyze_repetitions(const Curve& c, const IndentationParams& p) {
  validate(c, p);
  RepetitionSummary s;
  for (const Curve& one : split(c)) {
    try {
      s.per_rep.push_back(analyze_indentation(one, p));
    } catch (const DataError& e) {  // e.g. too few points in this repetition: say so, go on
      IndentationResult r;
      r.fit_reason = e.what();
      r.F0_N = p.force_constant_N_per_A * (p.bias_current_A - p.contact_current_A);
      r.tangent_depths_m = p.tangent_depths_m;
      for (Value* v : {&r.contact_z_m, &r.delta0_m, &r.k_tangent_at_delta0_N_per_m, &r.k_fd_N_per_m,
                       &r.k_window_N_per_m, &r.k_fd_paper_N_per_m, &r.k_window_paper_N_per_m})
        *v = Value::absent(e.what());
      r.k_tangent_N_per_m.assign(p.tangent_depths_m.size(), Value::absent(e.what()));
      s.per_rep.push_back(std::move(r));
    }
  }
  auto collect = [&](Value IndentationResult::*field) {
    std::vector<Value> v;
    for (const auto& r : s.per_rep) v.push_back(r.*field);
    return stat(v);
  };
  s.contact_z_m = collect(&IndentationResult::contact_z_m);
  s.delta0_m = collect(&IndentationResult::delta0_m);
  s.k_tangent_at_delta0_N_per_m = collect(&IndentationResult::k_tangent_at_delta0_N_per_m);
  s.k_fd_N_per_m = collect(&IndentationResult::k_fd_N_per_m);
  s.k_window_N_per_m = collect(&IndentationResult::k_window_N_per_m);
  s.k_fd_paper_N_per_m = collect(&IndentationResult::k_fd_paper_N_per_m);
  for (size_t k = 0; k < p.tangent_depths_m.size(); ++k) {
    std::vector<Value> v;
    for (const auto& r : s.per_rep) v.push_back(r.k_tangent_N_per_m[k]);
    s.k_tangent_N_per_m.push_back(stat(v));
  }
  return s;
}

}  // namespace palp::analysis
