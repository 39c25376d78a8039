// SPDX-License-Identifier: Apache-2.0
// Small builders for Vega 5 specifications (the report's figures, palp/report.hpp): a spec with
// its size, data sets embedded as "values", linear/log scales over domains computed here, axes
// whose titles carry units, line / symbol / band / rule / text / error-bar marks, a colour
// palette, and a heat map with a colour bar, links and outlined columns/rows. Every builder returns plain JSON that the caller may
// extend; nothing needs a browser to render (tooltips only add hover text in the page).
//
//   nlohmann::json s = vega::spec(560, 340);
//   vega::add_data(s, "curve", vega::rows({{"delta_mm", d}, {"F_N", f}}));
//   vega::Extent x, y;  x.add(d);  y.add(f);
//   vega::add_scale(s, vega::linear_scale("x", x, vega::Range::width));
//   vega::add_scale(s, vega::linear_scale("y", y, vega::Range::height));
//   vega::add_axes(s, "x", "δ (mm)", "y", "F_o (N)");
//   vega::add_mark(s, vega::line("curve", "x", "delta_mm", "y", "F_N", {vega::colour(0)}));
//
// Data: rows() zips named columns into Vega's row objects; a value that is not finite is written
// null, and line() / band() leave such points out (their "defined" channel), so a gap stays a
// gap. Units: the field names carry them (delta_mm, F_N), the axis titles say them.
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace palp::report::vega {

using nlohmann::json;

/// A new spec: "$schema" Vega 5, width/height (pixels of the plotting area), padding, autosize
/// "pad", white background, empty data/scales/axes/marks/legends arrays, and the title when one
/// is given (the report's figure heading is separate: keep it empty there).
json spec(int width, int height, const std::string& title = {});

/// Named columns of equal length zipped into rows [{name: value, ...}, ...]; a non-finite value
/// becomes null. Throws std::invalid_argument when the lengths differ.
using Column = std::pair<std::string, std::vector<double>>;
json rows(const std::vector<Column>& columns);
/// Appends {"name": name, "values": values} to spec["data"].
void add_data(json& spec, const std::string& name, json values);

/// The span of what a scale shows: add values (non-finite ones are ignored), then domain().
struct Extent {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v);
  void add(const std::vector<double>& v);
  bool empty() const { return !(lo <= hi); }
  /// [lo, hi] widened by `pad` of the span on each side; [lo - 1, hi + 1] for a single value and
  /// [0, 1] when empty. For a log scale use log_domain().
  json domain(double pad = 0.0) const;
  /// For a log scale: [lo / pad, hi * pad], lo replaced by hi / 10 when it is not positive;
  /// [1, 10] when empty or nothing is positive (add only positive values for a log axis).
  json log_domain(double pad = 1.0) const;
};

enum class Range { width, height };
/// Linear scale "name" over the domain; `nice` rounds to tick values; `zero` includes 0.
json linear_scale(const std::string& name, const Extent& e, Range range, bool zero = false,
                  bool nice = true, double pad = 0.02);
/// Log scale (base 10) over the positive part of the extent.
json log_scale(const std::string& name, const Extent& e, Range range);
/// Ordinal colour scale "name" over the given labels (a legend can use it): their colours, or
/// the palette in order when `colours` is empty. Throws std::invalid_argument when the counts
/// differ.
json colour_scale(const std::string& name, const std::vector<std::string>& labels,
                  const std::vector<std::string>& colours = {});
void add_scale(json& spec, json scale);

/// An axis with its title (the unit in it: "δ (mm)"), a grid, and an optional tick count and
/// label format ("~s", ".0f", ...).
json axis(const std::string& scale, const std::string& orient, const std::string& title,
          int tick_count = 0, const std::string& format = {}, bool grid = true);
/// The bottom x and left y axes.
void add_axes(json& spec, const std::string& x_scale, const std::string& x_title,
              const std::string& y_scale, const std::string& y_title);

/// Line style.
struct Stroke {
  std::string colour = "#1f77b4";
  double width = 1.5;
  std::vector<double> dash;  ///< empty: solid
  double opacity = 1.0;
};
/// A line through a data set's rows in their order (points with a null x or y are left out).
/// "name" is the mark's name: unique in the spec and never a data set's name (Vega makes a data
/// set of every named mark).
json line(const std::string& data, const std::string& x_scale, const std::string& x_field,
          const std::string& y_scale, const std::string& y_field, const Stroke& stroke,
          const std::string& name = {});
/// Points (circles unless `shape` says otherwise: "square", "diamond", "cross", "triangle-up").
json symbols(const std::string& data, const std::string& x_scale, const std::string& x_field,
             const std::string& y_scale, const std::string& y_field, const std::string& colour,
             double size = 30, const std::string& shape = "circle", const std::string& name = {});
/// A filled band between y_lo and y_hi along x (the mean ± s.d. band).
json band(const std::string& data, const std::string& x_scale, const std::string& x_field,
          const std::string& y_scale, const std::string& lo_field, const std::string& hi_field,
          const std::string& colour, double opacity = 0.25, const std::string& name = {});
/// Vertical error bars: one rule per row from lo_field to hi_field at x_field.
json error_bars(const std::string& data, const std::string& x_scale, const std::string& x_field,
                const std::string& y_scale, const std::string& lo_field,
                const std::string& hi_field, const std::string& colour,
                const std::string& name = {});
/// A vertical rule at x (data coordinates) across the plot, or a horizontal one at y.
json vertical_rule(const std::string& x_scale, double x, const Stroke& stroke,
                   const std::string& name = {});
json horizontal_rule(const std::string& y_scale, double y, const Stroke& stroke,
                     const std::string& name = {});
/// A text at data coordinates (dx, dy in pixels), left-aligned unless `align` says otherwise.
json text(const std::string& x_scale, double x, const std::string& y_scale, double y,
          const std::string& label, const std::string& colour = "#222", double dx = 4,
          double dy = -4, const std::string& align = "left", const std::string& name = {});
/// A text at a corner of the plotting area: "top-left", "top-right", "bottom-left",
/// "bottom-right" (a fit's parameters, R²).
json corner_text(const std::vector<std::string>& lines, const std::string& corner,
                 const std::string& colour = "#222", const std::string& name = {});
/// Adds a hover tooltip to a mark: the fields as "label: value" (labels carry their units).
void add_tooltip(json& mark, const std::vector<std::pair<std::string, std::string>>& fields);
void add_mark(json& spec, json mark);

/// A legend of the colour scale's entries drawn as `symbol` ("stroke": short lines), outside the
/// plot above it by default (so it hides no data), in rows of `columns` entries ("right": one
/// column beside the plot). Labels are not truncated.
json legend(const std::string& colour_scale, const std::string& title = {},
            const std::string& orient = "top", const std::string& symbol = "stroke",
            int columns = 3);

/// Palette (colour-blind safe, Okabe–Ito order, then greys); index wraps around.
std::string colour(int index);
const std::vector<std::string>& palette();

/// One cell of a heat map: grid position (1-based) and value; extra fields (shown on hover,
/// used by marks the caller adds) go into the row as they are.
struct HeatCell {
  int row = 0, column = 0;
  double value = 0;  ///< not finite: drawn grey ("no value")
  json extra = json::object();
};
struct HeatMapStyle {
  int cell_px = 40;                    ///< cell size (square cells)
  std::string value_title;             ///< the colour bar's title, with its unit: "k_fd (N/mm)"
  std::string scheme = "viridis";      ///< a Vega colour scheme
  bool reverse = false;                ///< reverse the scheme
  std::string format = ".3~f";         ///< the values' format (colour bar and cell labels)
  bool cell_labels = true;             ///< print the value in each cell
  std::string x_title = "column";      ///< axis titles (the grid's indices)
  std::string y_title = "row";
};
/// A heat map of rows x columns cells (row 1 at the top): data "cells" (row, column, value,
/// shade (the value's place 0..1 in the colour scheme), plus each cell's extra), band scales "x"
/// (columns) and "y" (rows), a sequential colour scale "colour" with a gradient legend (the
/// colour bar), a rect mark "heat_cells" with a hover tooltip (and a link when the cells' extra
/// hold "href": clicking a cell opens it, in the page and in the SVG), and the cell labels. Throws std::invalid_argument for rows or columns < 1 or a cell
/// outside the grid.
json heat_map(int rows, int columns, const std::vector<HeatCell>& cells,
              const HeatMapStyle& style);
/// Outlines whole columns (or rows) of a heat_map spec, e.g. the map's soft and stiff ones: one
/// rect per index around its cells (no fill), in `colour`, with `label` below a column (right of
/// a row, moving the colour bar clear of it) in the same colour. A rect mark named `name` (one
/// item per index) and a text mark `name`_label; data `name`_data.
void outline_columns(json& heat_map_spec, const std::vector<int>& columns,
                     const std::string& colour, const std::string& label, const std::string& name);
void outline_rows(json& heat_map_spec, const std::vector<int>& rows, const std::string& colour,
                  const std::string& label, const std::string& name);

}  // namespace palp::report::vega
