// SPDX-License-Identifier: Apache-2.0
// A dynamic map's grids in a map file (h5_map_dynamic.hpp).
#include "hdf5/h5_map_dynamic.hpp"

#include <limits>
#include <vector>

namespace palp::hdf5_detail {

void write_map_dynamic_grids(hid_t parent, const Where& w, const StiffnessMap& m) {
  const MapDynamicGrids g = map_dynamic_grids(m);
  if (g.points_identified == 0) return;
  const Id group = create_group(parent, w);
  const auto rows = static_cast<std::size_t>(g.rows), columns = static_cast<std::size_t>(g.columns);
  const auto grid = [&](const std::string& name, const std::vector<std::optional<double>>& v,
                        const char* unit) {
    std::vector<double> out(v.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t k = 0; k < v.size(); ++k)
      if (v[k]) out[k] = *v[k];
    put_grid(group.get(), name.c_str(), out, rows, columns, unit, w);
  };
  for (std::size_t q = 0; q < dynamic_quantities().size(); ++q) {
    const DynamicQuantity& d = dynamic_quantities()[q];
    grid(d.key, g.value[q], d.unit);
    grid(std::string(d.key) + "_se", g.se[q], d.unit);
  }
  put_attr(group.get(), "points_identified", static_cast<std::uint64_t>(g.points_identified), w);
}

std::string dynamic_group_name(const MapPoint& p) {
  return "r" + std::to_string(p.row) + "_c" + std::to_string(p.column) + "_dynamic";
}

}  // namespace palp::hdf5_detail
