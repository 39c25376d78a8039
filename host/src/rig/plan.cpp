// SPDX-License-Identifier: Apache-2.0
// plan.json: a grid (origin + pitch, or a region with n x m points) in a named work object.
#include <cmath>

#include "experiments/finite.hpp"
#include "json_fields.hpp"
#include "palp/error.hpp"
#include "palp/rig.hpp"

namespace palp {
namespace {


const std::vector<std::string> kPlanKeys = {"format_version", "name", "work_object", "grid",
                                            "contact_E_star_Pa", "approach_speed_mm_per_s"};
const std::vector<std::string> kGridKeys = {"rows",      "columns",    "origin_mm",
                                            "pitch_mm",  "x_range_mm", "y_range_mm"};

// The first point and pitch of n points spread over [lo, hi] (n = 1: lo, and lo must be hi).
void spread(const rig_detail::Fields& g, const std::string& key, int n, double& first,
            double& pitch) {
  const std::vector<double> v = g.numbers(key, 2);
  if (v[1] < v[0]) g.fail(key, "must be [min, max] with min <= max");
  if (n == 1 && v[1] != v[0]) g.fail(key, "a single point needs min = max");
  first = v[0] / format::kMm;
  pitch = n > 1 ? (v[1] - v[0]) / (n - 1) / format::kMm : 0.0;
}

}  // namespace

double Plan::x_m(int column) const {
  if (column < 0 || column >= grid.columns) {
    throw ConfigError("plan " + name + ": no column " + std::to_string(column) +
                      " (0-based) in a grid of " + std::to_string(grid.columns));
  }
  return grid.x0_m + column * grid.pitch_x_m;
}

double Plan::y_m(int row) const {
  if (row < 0 || row >= grid.rows) {
    throw ConfigError("plan " + name + ": no row " + std::to_string(row) +
                      " (0-based) in a grid of " + std::to_string(grid.rows));
  }
  return grid.y0_m + row * grid.pitch_y_m;
}

std::pair<double, double> Plan::point_m(int row, int column) const {
  return {x_m(column), y_m(row)};
}

void Plan::validate() const {
  const std::string who = "plan " + name;
  experiment::require_finite(who, {{"grid.x0_m", grid.x0_m}, {"grid.y0_m", grid.y0_m},
                                   {"grid.pitch_x_m", grid.pitch_x_m}, {"grid.pitch_y_m", grid.pitch_y_m},
                                   {"contact_E_star_Pa", contact_E_star_Pa.value_or(1.0)},
                                   {"approach_speed_m_per_s", approach_speed_m_per_s.value_or(1.0)}});
  if (grid.rows < 1 || grid.rows > 1000 || grid.columns < 1 || grid.columns > 1000)
    throw ConfigError(who + ": a " + std::to_string(grid.rows) + " x " + std::to_string(grid.columns) +
                      " grid; rows and columns must lie in 1..1000");
}

Plan parse_plan(std::string_view text, std::string_view source) {
  const rig_detail::Fields f(text, std::string(source), kPlanKeys);
  f.require({"format_version", "name", "work_object", "grid"});
  f.integer("format_version", 1, 1);
  Plan p;
  p.name = f.text("name");
  p.work_object = f.text("work_object");
  const rig_detail::Fields g(f, "grid", kGridKeys);
  g.require({"rows", "columns"});
  PlanGrid& q = p.grid;
  q.rows = g.integer("rows", 1, 1000);
  q.columns = g.integer("columns", 1, 1000);
  const bool pitch = g.has("origin_mm") || g.has("pitch_mm");
  const bool region = g.has("x_range_mm") || g.has("y_range_mm");
  if (pitch && region) {
    g.fail(region ? (g.has("x_range_mm") ? "x_range_mm" : "y_range_mm") : "origin_mm",
           "give either origin_mm + pitch_mm or x_range_mm + y_range_mm, not both");
  }
  if (region) {
    g.require({"x_range_mm", "y_range_mm"});
    spread(g, "x_range_mm", q.columns, q.x0_m, q.pitch_x_m);
    spread(g, "y_range_mm", q.rows, q.y0_m, q.pitch_y_m);
  } else {
    g.require({"origin_mm", "pitch_mm"});
    const std::vector<double> o = g.numbers("origin_mm", 2);
    const std::vector<double> d = g.numbers("pitch_mm", 2);
    q.x0_m = o[0] / format::kMm;
    q.y0_m = o[1] / format::kMm;
    q.pitch_x_m = d[0] / format::kMm;
    q.pitch_y_m = d[1] / format::kMm;
    if ((q.columns > 1 && !(d[0] > 0.0)) || (q.rows > 1 && !(d[1] > 0.0))) {
      g.fail("pitch_mm", "must be > 0 mm along every axis with more than one point");
    }
  }
  if (f.has("contact_E_star_Pa")) p.contact_E_star_Pa = f.positive("contact_E_star_Pa", 1e12, "Pa");
  if (f.has("approach_speed_mm_per_s")) {
    p.approach_speed_m_per_s = f.positive("approach_speed_mm_per_s", 100.0, "mm/s") / format::kMm;
  }
  return p;
}

Plan load_plan(const std::filesystem::path& file) {
  return parse_plan(rig_detail::read_file(file.string()), file.string());
}

}  // namespace palp
