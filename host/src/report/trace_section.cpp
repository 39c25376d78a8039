// SPDX-License-Identifier: Apache-2.0
// The trace section (sections.hpp): a traced surface as two heat maps on its grid, each with a
// colour bar: the zero-force contact points' z (mm, work-object frame, +z into the specimen)
// and the normals' tilts from the work object's z (degrees), with a tick in each cell pointing
// along the normal's horizontal part (its length grows with the tilt). A point without contact
// is grey; hovering a cell shows its values (or why it has none).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "palp/error.hpp"
#include "report/section_format.hpp"
#include "report/sections.hpp"
#include "report/vega_build.hpp"

namespace palp::report {

namespace trace_figures {

using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;

int cell_px(const TracedSurface& s) { return std::clamp(480 / std::max(s.rows, s.columns), 24, 56); }

json extra_of(const TracePoint& p) {
  return {{"x_mm", p.x_m * 1e3},
          {"y_mm", p.y_m * 1e3},
          {"z_mm", p.ok ? json(p.z_m * 1e3) : json(nullptr)},
          {"tilt_deg", p.ok ? json(p.tilt_rad * 180.0 / kPi) : json(nullptr)},
          {"status", p.ok ? std::string("ok") : p.reason}};
}

json heights_spec(const TracedSurface& s) {
  std::vector<vega::HeatCell> cells;
  for (const auto& p : s.points)
    cells.push_back({p.row, p.column, p.ok ? p.z_m * 1e3 : std::nan(""), extra_of(p)});
  vega::HeatMapStyle style;
  style.cell_px = cell_px(s);
  style.value_title = "z (mm)";
  style.format = ".3f";
  style.cell_labels = style.cell_px >= 40;
  json spec = vega::heat_map(s.rows, s.columns, cells, style);
  spec["marks"][0]["encode"]["enter"]["tooltip"] = {
      {"signal", "{'row': datum.row, 'column': datum.column, 'x (mm)': format(datum.x_mm, '.2f'), "
                 "'y (mm)': format(datum.y_mm, '.2f'), 'z (mm)': isValid(datum.z_mm) ? "
                 "format(datum.z_mm, '.3f') : datum.status}"}};
  return spec;
}

json tilts_spec(const TracedSurface& s) {
  std::vector<vega::HeatCell> cells;
  double max_tilt = 0;
  for (const auto& p : s.points)
    if (p.ok) max_tilt = std::max(max_tilt, p.tilt_rad);
  const int px = cell_px(s);
  for (const auto& p : s.points) {
    json extra = extra_of(p);
    // the normal's horizontal direction, drawn as a tick from the cell's centre (y down on screen:
    // a row further down the grid is a larger work-object y, so the sign stays)
    const double h = std::hypot(p.normal[0], p.normal[1]);
    const double length = max_tilt > 0 ? 0.42 * px * p.tilt_rad / max_tilt : 0.0;
    extra["dx_px"] = p.ok && h > 0 ? length * p.normal[0] / h : 0.0;
    extra["dy_px"] = p.ok && h > 0 ? length * p.normal[1] / h : 0.0;
    cells.push_back({p.row, p.column, p.ok ? p.tilt_rad * 180.0 / kPi : std::nan(""), extra});
  }
  vega::HeatMapStyle style;
  style.cell_px = px;
  style.value_title = "tilt (deg)";
  style.scheme = "magma";
  style.format = ".2f";
  style.cell_labels = false;
  json spec = vega::heat_map(s.rows, s.columns, cells, style);
  spec["marks"][0]["encode"]["enter"]["tooltip"] = {
      {"signal", "{'row': datum.row, 'column': datum.column, 'tilt (deg)': isValid(datum.tilt_deg) ? "
                 "format(datum.tilt_deg, '.2f') : datum.status}"}};
  const std::string cx = "scale('x', datum.column) + bandwidth('x') / 2";
  const std::string cy = "scale('y', datum.row) + bandwidth('y') / 2";
  json ticks = {{"type", "rule"},
                {"name", "normal_ticks"},
                {"from", {{"data", "cells"}}},
                {"encode",
                 {{"enter",
                   {{"x", {{"signal", cx}}},
                    {"y", {{"signal", cy}}},
                    {"x2", {{"signal", cx + " + datum.dx_px"}}},
                    {"y2", {{"signal", cy + " + datum.dy_px"}}},
                    {"stroke", {{"signal", "datum.shade < 0.55 ? 'white' : 'black'"}}},
                    {"strokeWidth", {{"value", 2}}},
                    {"strokeCap", {{"value", "round"}}}}}}}};
  vega::add_mark(spec, std::move(ticks));
  json dots = {{"type", "symbol"},
               {"name", "normal_feet"},
               {"from", {{"data", "cells"}}},
               {"encode",
                {{"enter",
                  {{"x", {{"signal", cx}}},
                   {"y", {{"signal", cy}}},
                   {"size", {{"value", 10}}},
                   {"fill", {{"signal", "datum.shade < 0.55 ? 'white' : 'black'"}}},
                   {"opacity", {{"signal", "isValid(datum.value) ? 1 : 0"}}}}}}}};
  vega::add_mark(spec, std::move(dots));
  return spec;
}

}  // namespace trace_figures

Section trace_section(const TracedSurface& surface) {
  namespace fig = trace_figures;
  if (surface.rows < 1 || surface.columns < 1)
    throw ConfigError("trace_section: the trace \"" + surface.plan_name + "\" has a " +
                      std::to_string(surface.rows) + " x " + std::to_string(surface.columns) + " grid");
  for (const auto& p : surface.points)
    if (p.row < 1 || p.row > surface.rows || p.column < 1 || p.column > surface.columns)
      throw ConfigError("trace_section: the trace \"" + surface.plan_name + "\" has a point at row " +
                        std::to_string(p.row) + ", column " + std::to_string(p.column) +
                        ", outside its " + std::to_string(surface.rows) + " x " +
                        std::to_string(surface.columns) + " grid");
  Section s;
  s.id = "trace";
  s.title = "Surface trace " + surface.plan_name;
  const auto ok = std::count_if(surface.points.begin(), surface.points.end(),
                                [](const TracePoint& p) { return p.ok; });
  s.text = std::to_string(ok) + " of " + std::to_string(surface.rows * surface.columns) +
           " grid points traced" + (surface.complete ? "" : " (incomplete: " + surface.stopped_because + ")") +
           "; normals " + (surface.normals_from_grid ? "from the neighbouring points" : "along the approach axis") +
           ", tip radius " + format_number(surface.tip_radius_m * 1e3) + " mm.";
  s.figures.push_back({"trace-heights", "Contact heights",
                       "The zero-force contact point's z at each grid point (work-object frame, mm, "
                       "+z into the specimen); grey: no contact.",
                       fig::heights_spec(surface)});
  s.figures.push_back({"trace-tilts", "Surface normals' tilt",
                       "The angle between each point's surface normal and the work object's z "
                       "(degrees); the tick points along the normal's horizontal part, longer for "
                       "a larger tilt.",
                       fig::tilts_spec(surface)});
  return s;
}

}  // namespace palp::report
