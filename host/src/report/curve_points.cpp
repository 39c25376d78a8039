// SPDX-License-Identifier: Apache-2.0
#include "report/curve_points.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace palp::report {

std::vector<int> repetitions_of(const analysis::Curve& c) {
  std::vector<int> reps;
  for (Eigen::Index k = 0; k < c.rep.size(); ++k)
    if (std::find(reps.begin(), reps.end(), c.rep[k]) == reps.end()) reps.push_back(c.rep[k]);
  return reps;
}

std::vector<PointGroup> plateau_groups(const analysis::Curve& c, int max_per_rep) {
  const Eigen::Index n = c.z_m.size();
  std::vector<bool> loading(static_cast<std::size_t>(n), false);
  for (int k : analysis::loading_branch(c).loading) loading[static_cast<std::size_t>(k)] = true;
  const bool plateaus = c.i_cmd_A.size() == n;
  std::map<int, Eigen::Index> per_rep;  // samples per repetition, for the stride
  for (Eigen::Index k = 0; k < n; ++k) ++per_rep[c.rep.size() == n ? c.rep[k] : 0];
  std::vector<PointGroup> groups;
  for (Eigen::Index k = 0; k < n; ++k) {
    const int rep = c.rep.size() == n ? c.rep[k] : 0;
    const bool load = loading[static_cast<std::size_t>(k)];
    bool same = !groups.empty() && groups.back().rep == rep && groups.back().loading == load;
    if (same && plateaus) same = c.i_cmd_A[k] == c.i_cmd_A[groups.back().samples.front()];
    if (same && !plateaus) {
      const Eigen::Index stride = std::max<Eigen::Index>(1, (per_rep[rep] + max_per_rep - 1) / max_per_rep);
      same = static_cast<Eigen::Index>(groups.back().samples.size()) < stride;
    }
    if (!same) groups.push_back({rep, load, {}});
    groups.back().samples.push_back(k);
  }
  return groups;
}

std::vector<Level> levels_over_repetitions(const analysis::Curve& c,
                                           const std::vector<PointGroup>& groups) {
  std::vector<Level> levels;
  if (c.i_cmd_A.size() != c.z_m.size()) return levels;
  // keyed by branch and current (to the microampere: the ramp's levels are float set-points)
  std::map<std::pair<int, long long>, std::size_t> index;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const double i = c.i_cmd_A[groups[g].samples.front()];
    const auto key = std::make_pair(groups[g].loading ? 0 : 1, std::llround(i * 1e6) * (groups[g].loading ? 1 : -1));
    auto [it, fresh] = index.emplace(key, levels.size());
    if (fresh) levels.push_back({groups[g].loading, i, {}});
    levels[it->second].groups.push_back(g);
  }
  std::vector<Level> ordered;
  for (const auto& [key, at] : index) ordered.push_back(std::move(levels[at]));
  return ordered;
}

double group_mean(const Eigen::VectorXd& v, const PointGroup& g) {
  double s = 0.0;
  for (Eigen::Index k : g.samples) s += v[k];
  return g.samples.empty() ? 0.0 : s / static_cast<double>(g.samples.size());
}

}  // namespace palp::report
