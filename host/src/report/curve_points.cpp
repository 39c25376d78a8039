#include "report/curve_points.hpp"

#include <algorithm>
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

double group_mean(const Eigen::VectorXd& v, const PointGroup& g) {
  double s = 0.0;
  for (Eigen::Index k : g.samples) s += v[k];
  return g.samples.empty() ? 0.0 : s / static_cast<double>(g.samples.size());
}

}  // namespace palp::report
