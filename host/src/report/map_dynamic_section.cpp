// SPDX-License-Identifier: Apache-2.0
// A dynamic map's section (palp/map_dynamic.hpp): one heat map per quantity (ω_n, ζ, m_eff, b_o,
// E′, E″) on the map's grid, each cell's value ± its standard error on hover and a link to the
// point's identification; a table of the column means.
#include <cmath>
#include <string>
#include <vector>

#include "palp/map_dynamic.hpp"
#include "report/report_internal.hpp"
#include "report/sections.hpp"
#include "report/vega_build.hpp"

namespace palp::report {

using detail::num;
using nlohmann::json;

namespace {

constexpr int kDynamicCellPx = 40;

/// The colour bar's and the cells' number format per quantity (dynamic_quantities' order).
const char* dynamic_format_of(const std::string& key) {
  if (key == "omega_n_rad_per_s") return ".1f";
  if (key == "zeta") return ".3f";
  if (key == "m_eff_kg") return ".3f";
  if (key == "b_o_N_s_per_m") return ".2f";
  return ".3~s";  // the moduli, Pa: 1.21M
}

}  // namespace

Section map_dynamic_section(const StiffnessMap& map) {
  const MapDynamicGrids g = map_dynamic_grids(map);
  Section s;
  s.id = "map-dynamic";
  s.title = "Viscoelastic map";
  std::string band;
  if (map.dynamic)
    band = " The identification: a " + std::string(sweep_method_name(map.dynamic->method)) +
           " of " + num(map.dynamic->amplitude_A) + " A peak about the bias " +
           num(map.dynamic->bias_A) + " A over " + num(map.dynamic->f_lo_Hz) + "–" +
           num(map.dynamic->f_hi_Hz) + " Hz, " + std::to_string(map.dynamic->measured_periods) +
           " periods of " + num(1.0 / map.dynamic->fundamental_Hz) + " s measured.";
  s.text = "At each point, after the quasi-static ramp, the contact was identified at the bias (" +
           std::to_string(g.points_identified) + " of " + std::to_string(g.rows * g.columns) +
           " points): ω_n and ζ of the second-order fit; m_eff = (k_v + k_o)/ω_n² and "
           "b_o = 2ζ(k_v + k_o)/ω_n − b_v with the static tangent k_o at δ0; E′ and E″ the "
           "contact's storage and loss moduli k′/(2a), k″/(2a), averaged over the measured lines." +
           band;
  for (std::size_t q = 0; q < dynamic_quantities().size(); ++q) {
    const DynamicQuantity& d = dynamic_quantities()[q];
    std::vector<vega::HeatCell> cells;
    for (const MapPoint& p : map.points) {
      if (p.row < 1 || p.row > map.rows || p.column < 1 || p.column > map.columns) continue;
      const auto at = static_cast<std::size_t>((p.row - 1) * map.columns + p.column - 1);
      vega::HeatCell c;
      c.row = p.row;
      c.column = p.column;
      c.value = g.value[q][at].value_or(NAN);
      c.extra = {{"se", g.se[q][at] ? json(*g.se[q][at]) : json(nullptr)},
                 {"reason", p.dynamic.reason.empty() ? "–" : p.dynamic.reason}};
      if (!p.dynamic_dir.empty()) c.extra["href"] = p.dynamic_dir + "/result.json";
      cells.push_back(std::move(c));
    }
    vega::HeatMapStyle style;
    style.cell_px = kDynamicCellPx;
    style.value_title = d.title;
    style.format = dynamic_format_of(d.key);
    json spec = vega::heat_map(map.rows, map.columns, cells, style);
    for (json& m : spec["marks"])
      if (m.value("name", "") == "heat_cells")
        m["encode"]["enter"]["tooltip"] = {
            {"signal", "{'point': 'row ' + datum.row + ', column ' + datum.column, '" +
                           std::string(d.title) +
                           "': isValid(datum.value) ? format(datum.value, '.4~g') + "
                           "(isValid(datum.se) ? ' ± ' + "
                           "format(datum.se, '.2~g') : '') : '–', 'reason': datum.reason}"}};
    spec["description"] = std::string(d.title) + " heat map of a dynamic map";
    Figure f;
    f.id = std::string("map-dynamic-") + d.key;
    f.title = std::string(d.title) + " per grid point";
    f.caption = std::string(d.title) +
                " at each point (grey: none), rows down and columns across as the k_fd map. "
                "In the page, hover a cell for its value ± standard error; click it to open its "
                "identification.";
    f.spec = std::move(spec);
    s.figures.push_back(std::move(f));
  }
  Table t;
  t.id = "map-dynamic-columns";
  t.title = "Column means of the dynamic quantities";
  t.columns = {"column"};
  for (const DynamicQuantity& d : dynamic_quantities()) t.columns.push_back(d.title);
  for (int c = 1; c <= map.columns; ++c) {
    std::vector<std::string> row = {std::to_string(c)};
    for (std::size_t q = 0; q < dynamic_quantities().size(); ++q) {
      double sum = 0;
      int n = 0;
      for (int r = 1; r <= map.rows; ++r)
        if (const auto& v = g.value[q][static_cast<std::size_t>((r - 1) * map.columns + c - 1)])
          sum += *v, ++n;
      row.push_back(n > 0 ? num(sum / n) : "–");
    }
    t.rows.push_back(std::move(row));
  }
  t.caption = "Means over each column's points with a value.";
  s.tables.push_back(std::move(t));
  return s;
}

}  // namespace palp::report
