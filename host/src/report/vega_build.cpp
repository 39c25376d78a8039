// SPDX-License-Identifier: Apache-2.0
#include "report/vega_build.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace palp::report::vega {

namespace {

// datum['field'] (field names carry units and may hold characters an identifier cannot)
std::string datum(const std::string& field) { return "datum['" + field + "']"; }

json scaled(const std::string& scale, const std::string& field) {
  return {{"scale", scale}, {"field", field}};
}

json defined(const std::vector<std::string>& fields) {
  std::string expr;
  for (const auto& f : fields) {
    if (!expr.empty()) expr += " && ";
    expr += "isValid(" + datum(f) + ") && isFinite(" + datum(f) + ")";
  }
  return {{"signal", expr}};
}

void name_mark(json& mark, const std::string& name) {
  if (!name.empty()) mark["name"] = name;
}

json stroke_encoding(const Stroke& s) {
  json e = {{"stroke", {{"value", s.colour}}},
            {"strokeWidth", {{"value", s.width}}},
            {"strokeOpacity", {{"value", s.opacity}}}};
  if (!s.dash.empty()) e["strokeDash"] = {{"value", s.dash}};
  return e;
}

}  // namespace

json spec(int width, int height, const std::string& title) {
  json s = {{"$schema", "https://vega.github.io/schema/vega/v5.json"},
            {"width", width},
            {"height", height},
            {"padding", 8},
            {"autosize", {{"type", "pad"}}},
            {"background", "white"},
            {"config", {{"axis", {{"labelFontSize", 11}, {"titleFontSize", 12}}},
                        {"legend", {{"labelFontSize", 11}, {"titleFontSize", 11}}}}},
            {"data", json::array()},
            {"scales", json::array()},
            {"axes", json::array()},
            {"legends", json::array()},
            {"marks", json::array()}};
  if (!title.empty()) s["title"] = {{"text", title}, {"anchor", "start"}};
  return s;
}

json rows(const std::vector<Column>& columns) {
  json out = json::array();
  if (columns.empty()) return out;
  const std::size_t n = columns.front().second.size();
  for (const auto& [name, values] : columns) {
    if (values.size() != n)
      throw std::invalid_argument("vega::rows: column \"" + name + "\" has " +
                                  std::to_string(values.size()) + " values, \"" +
                                  columns.front().first + "\" has " + std::to_string(n));
  }
  for (std::size_t i = 0; i < n; ++i) {
    json row = json::object();
    for (const auto& [name, values] : columns)
      row[name] = std::isfinite(values[i]) ? json(values[i]) : json(nullptr);
    out.push_back(std::move(row));
  }
  return out;
}

void add_data(json& spec, const std::string& name, json values) {
  spec["data"].push_back({{"name", name}, {"values", std::move(values)}});
}

void Extent::add(double v) {
  if (!std::isfinite(v)) return;
  lo = std::min(lo, v);
  hi = std::max(hi, v);
}

void Extent::add(const std::vector<double>& v) {
  for (double x : v) add(x);
}

json Extent::domain(double pad) const {
  if (empty()) return json::array({0.0, 1.0});
  if (hi == lo) return json::array({lo - 1.0, hi + 1.0});
  const double margin = (hi - lo) * pad;
  return json::array({lo - margin, hi + margin});
}

json Extent::log_domain(double pad) const {
  // lo/hi may include non-positive values: the caller adds only positive ones for a log axis
  if (empty() || hi <= 0) return json::array({1.0, 10.0});
  const double l = lo > 0 ? lo : hi / 10.0;
  if (hi == l) return json::array({l / 10.0, hi * 10.0});
  return json::array({l / pad, hi * pad});
}

json linear_scale(const std::string& name, const Extent& e, Range range, bool zero, bool nice,
                  double pad) {
  return {{"name", name},
          {"type", "linear"},
          {"domain", e.domain(pad)},
          {"range", range == Range::width ? "width" : "height"},
          {"zero", zero},
          {"nice", nice}};
}

json log_scale(const std::string& name, const Extent& e, Range range) {
  return {{"name", name},
          {"type", "log"},
          {"base", 10},
          {"domain", e.log_domain(1.15)},
          {"range", range == Range::width ? "width" : "height"},
          {"nice", false}};
}

json colour_scale(const std::string& name, const std::vector<std::string>& labels,
                  const std::vector<std::string>& colours) {
  if (!colours.empty() && colours.size() != labels.size())
    throw std::invalid_argument("vega::colour_scale: " + std::to_string(labels.size()) +
                                " labels, " + std::to_string(colours.size()) + " colours");
  json range = json::array();
  for (std::size_t i = 0; i < labels.size(); ++i)
    range.push_back(colours.empty() ? colour(static_cast<int>(i)) : colours[i]);
  return {{"name", name}, {"type", "ordinal"}, {"domain", labels}, {"range", range}};
}

void add_scale(json& spec, json scale) { spec["scales"].push_back(std::move(scale)); }

json axis(const std::string& scale, const std::string& orient, const std::string& title,
          int tick_count, const std::string& format, bool grid) {
  json a = {{"scale", scale}, {"orient", orient}, {"title", title}, {"grid", grid},
            {"gridOpacity", 0.35}};
  if (tick_count > 0) a["tickCount"] = tick_count;
  if (!format.empty()) a["format"] = format;
  return a;
}

void add_axes(json& spec, const std::string& x_scale, const std::string& x_title,
              const std::string& y_scale, const std::string& y_title) {
  spec["axes"].push_back(axis(x_scale, "bottom", x_title));
  spec["axes"].push_back(axis(y_scale, "left", y_title));
}

json line(const std::string& data, const std::string& x_scale, const std::string& x_field,
          const std::string& y_scale, const std::string& y_field, const Stroke& stroke,
          const std::string& name) {
  json enter = stroke_encoding(stroke);
  enter["x"] = scaled(x_scale, x_field);
  enter["y"] = scaled(y_scale, y_field);
  enter["defined"] = defined({x_field, y_field});
  json m = {{"type", "line"}, {"from", {{"data", data}}}, {"clip", true},
            {"encode", {{"enter", enter}}}};
  name_mark(m, name);
  return m;
}

json symbols(const std::string& data, const std::string& x_scale, const std::string& x_field,
             const std::string& y_scale, const std::string& y_field, const std::string& colour,
             double size, const std::string& shape, const std::string& name) {
  json enter = {{"x", scaled(x_scale, x_field)},
                {"y", scaled(y_scale, y_field)},
                {"shape", {{"value", shape}}},
                {"size", {{"value", size}}},
                {"stroke", {{"value", colour}}},
                {"strokeWidth", {{"value", 1.2}}},
                {"fill", {{"value", colour}}},
                {"fillOpacity", {{"value", 0.55}}}};
  json m = {{"type", "symbol"}, {"from", {{"data", data}}}, {"clip", true},
            {"encode", {{"enter", enter}}}};
  name_mark(m, name);
  return m;
}

json band(const std::string& data, const std::string& x_scale, const std::string& x_field,
          const std::string& y_scale, const std::string& lo_field, const std::string& hi_field,
          const std::string& colour, double opacity, const std::string& name) {
  json enter = {{"x", scaled(x_scale, x_field)},
                {"y", scaled(y_scale, lo_field)},
                {"y2", scaled(y_scale, hi_field)},
                {"fill", {{"value", colour}}},
                {"fillOpacity", {{"value", opacity}}},
                {"defined", defined({x_field, lo_field, hi_field})}};
  json m = {{"type", "area"}, {"from", {{"data", data}}}, {"clip", true},
            {"encode", {{"enter", enter}}}};
  name_mark(m, name);
  return m;
}

json error_bars(const std::string& data, const std::string& x_scale, const std::string& x_field,
                const std::string& y_scale, const std::string& lo_field,
                const std::string& hi_field, const std::string& colour,
                const std::string& name) {
  json enter = {{"x", scaled(x_scale, x_field)},
                {"y", scaled(y_scale, lo_field)},
                {"y2", scaled(y_scale, hi_field)},
                {"stroke", {{"value", colour}}},
                {"strokeWidth", {{"value", 1.2}}}};
  json m = {{"type", "rule"}, {"from", {{"data", data}}}, {"clip", true},
            {"encode", {{"enter", enter}}}};
  name_mark(m, name);
  return m;
}

json vertical_rule(const std::string& x_scale, double x, const Stroke& stroke,
                   const std::string& name) {
  json enter = stroke_encoding(stroke);
  enter["x"] = {{"scale", x_scale}, {"value", x}};
  enter["y"] = {{"value", 0}};
  enter["y2"] = {{"signal", "height"}};
  json m = {{"type", "rule"}, {"clip", true}, {"encode", {{"enter", enter}}}};
  name_mark(m, name);
  return m;
}

json horizontal_rule(const std::string& y_scale, double y, const Stroke& stroke,
                     const std::string& name) {
  json enter = stroke_encoding(stroke);
  enter["y"] = {{"scale", y_scale}, {"value", y}};
  enter["x"] = {{"value", 0}};
  enter["x2"] = {{"signal", "width"}};
  json m = {{"type", "rule"}, {"clip", true}, {"encode", {{"enter", enter}}}};
  name_mark(m, name);
  return m;
}

json text(const std::string& x_scale, double x, const std::string& y_scale, double y,
          const std::string& label, const std::string& colour, double dx, double dy,
          const std::string& align, const std::string& name) {
  json enter = {{"x", {{"scale", x_scale}, {"value", x}}},
                {"y", {{"scale", y_scale}, {"value", y}}},
                {"dx", {{"value", dx}}},
                {"dy", {{"value", dy}}},
                {"text", {{"value", label}}},
                {"align", {{"value", align}}},
                {"fill", {{"value", colour}}},
                {"fontSize", {{"value", 11}}}};
  json m = {{"type", "text"}, {"encode", {{"enter", enter}}}};
  name_mark(m, name);
  return m;
}

json corner_text(const std::vector<std::string>& lines, const std::string& corner,
                 const std::string& colour, const std::string& name) {
  const bool right = corner.find("right") != std::string::npos;
  const bool bottom = corner.find("bottom") != std::string::npos;
  json enter = {{"x", right ? json{{"signal", "width"}, {"offset", -6}} : json{{"value", 6}}},
                // a multi-line text grows downwards from y: lift it by its lines
                {"y", bottom ? json{{"signal", "height"},
                                    {"offset", -6 - 14 * (static_cast<int>(lines.size()) - 1)}}
                             : json{{"value", 6}}},
                {"text", {{"value", lines}}},
                {"align", {{"value", right ? "right" : "left"}}},
                {"baseline", {{"value", bottom ? "bottom" : "top"}}},
                {"lineHeight", {{"value", 14}}},
                {"fill", {{"value", colour}}},
                {"fontSize", {{"value", 11}}}};
  json m = {{"type", "text"}, {"encode", {{"enter", enter}}}};
  name_mark(m, name);
  return m;
}

void add_tooltip(json& mark, const std::vector<std::pair<std::string, std::string>>& fields) {
  std::string expr = "{";
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i) expr += ", ";
    expr += "'" + fields[i].first + "': " + datum(fields[i].second);
  }
  expr += "}";
  mark["encode"]["enter"]["tooltip"] = {{"signal", expr}};
}

void add_mark(json& spec, json mark) { spec["marks"].push_back(std::move(mark)); }

json legend(const std::string& colour_scale, const std::string& title, const std::string& orient,
            const std::string& symbol, int columns) {
  json l = {{"stroke", colour_scale},
            {"orient", orient},
            {"symbolType", symbol},
            {"symbolStrokeWidth", 2},
            {"labelLimit", 0},
            {"columnPadding", 14},
            {"padding", 2}};
  if (orient == "right" || orient == "left") {
    l["direction"] = "vertical";
  } else {
    l["direction"] = "horizontal";
    if (columns > 0) l["columns"] = columns;
  }
  if (!title.empty()) l["title"] = title;
  return l;
}

const std::vector<std::string>& palette() {
  static const std::vector<std::string> p = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                             "#E69F00", "#56B4E9", "#000000", "#F0E442",
                                             "#777777", "#AAAAAA"};
  return p;
}

std::string colour(int index) {
  const auto& p = palette();
  const int n = static_cast<int>(p.size());
  return p[static_cast<std::size_t>(((index % n) + n) % n)];
}

json heat_map(int rows_n, int columns, const std::vector<HeatCell>& cells,
              const HeatMapStyle& style) {
  if (rows_n < 1 || columns < 1)
    throw std::invalid_argument("vega::heat_map: a grid of " + std::to_string(rows_n) + " x " +
                                std::to_string(columns) + " cells");
  Extent e;
  for (const auto& c : cells) {
    if (c.row < 1 || c.row > rows_n || c.column < 1 || c.column > columns)
      throw std::invalid_argument("vega::heat_map: cell (" + std::to_string(c.row) + ", " +
                                  std::to_string(c.column) + ") outside the " +
                                  std::to_string(rows_n) + " x " + std::to_string(columns) +
                                  " grid");
    e.add(c.value);
  }
  json values = json::array();
  for (const auto& c : cells) {
    json row = c.extra.is_object() ? c.extra : json::object();
    row["row"] = c.row;
    row["column"] = c.column;
    const bool ok = std::isfinite(c.value);
    row["value"] = ok ? json(c.value) : json(nullptr);
    // the value's place in the colour scale (0..1): the labels' ink flips on dark cells
    double t = 0.5;
    if (ok && e.hi > e.lo) t = (c.value - e.lo) / (e.hi - e.lo);
    if (style.reverse) t = 1.0 - t;
    row["shade"] = t;
    values.push_back(std::move(row));
  }
  json s = spec(style.cell_px * columns, style.cell_px * rows_n);
  add_data(s, "cells", std::move(values));
  json col_domain = json::array(), row_domain = json::array();
  for (int c = 1; c <= columns; ++c) col_domain.push_back(c);
  for (int r = 1; r <= rows_n; ++r) row_domain.push_back(r);
  add_scale(s, {{"name", "x"}, {"type", "band"}, {"domain", col_domain}, {"range", "width"},
                {"padding", 0.04}});
  add_scale(s, {{"name", "y"}, {"type", "band"}, {"domain", row_domain}, {"range", "height"},
                {"padding", 0.04}});
  json colour_domain = e.empty() ? json::array({0.0, 1.0})
                                 : (e.hi > e.lo ? json::array({e.lo, e.hi})
                                                : json::array({e.lo - 1.0, e.hi + 1.0}));
  add_scale(s, {{"name", "colour"}, {"type", "linear"}, {"domain", colour_domain},
                {"range", {{"scheme", style.scheme}}}, {"reverse", style.reverse},
                {"zero", false}, {"nice", false}});
  s["axes"].push_back(axis("x", "top", style.x_title, 0, {}, false));
  s["axes"].push_back(axis("y", "left", style.y_title, 0, {}, false));
  s["legends"].push_back({{"fill", "colour"},
                          {"type", "gradient"},
                          {"title", style.value_title},
                          {"format", style.format},
                          {"orient", "right"},
                          {"gradientLength", std::max(120, style.cell_px * rows_n)},
                          {"gradientThickness", 14}});
  json rect = {
      {"type", "rect"},
      {"name", "heat_cells"},
      {"from", {{"data", "cells"}}},
      {"encode",
       {{"enter",
         {{"x", {{"scale", "x"}, {"field", "column"}}},
          {"width", {{"scale", "x"}, {"band", 1}}},
          {"y", {{"scale", "y"}, {"field", "row"}}},
          {"height", {{"scale", "y"}, {"band", 1}}},
          {"fill", {{"signal", "isValid(datum.value) ? scale('colour', datum.value) : '#d0d0d0'"}}},
          {"tooltip",
           {{"signal", "{'row': datum.row, 'column': datum.column, '" + style.value_title +
                           "': isValid(datum.value) ? format(datum.value, '" + style.format +
                           "') : 'no value'}"}}}}}}}};
  const bool links = std::any_of(cells.begin(), cells.end(), [](const HeatCell& c) {
    return c.extra.is_object() && c.extra.contains("href");
  });
  if (links) {
    rect["encode"]["enter"]["href"] = {{"field", "href"}};
    rect["encode"]["enter"]["cursor"] = {{"value", "pointer"}};
  }
  add_mark(s, std::move(rect));
  if (style.cell_labels) {
    json label = {
        {"type", "text"},
        {"name", "cell_labels"},
        {"from", {{"data", "cells"}}},
        {"encode",
         {{"enter",
           {{"x", {{"scale", "x"}, {"field", "column"}, {"band", 0.5}}},
            {"y", {{"scale", "y"}, {"field", "row"}, {"band", 0.5}}},
            {"align", {{"value", "center"}}},
            {"baseline", {{"value", "middle"}}},
            {"fontSize", {{"value", 10}}},
            {"text", {{"signal", "isValid(datum.value) ? format(datum.value, '" + style.format +
                                     "') : '–'"}}},
            {"fill", {{"signal", "datum.shade < 0.55 ? 'white' : 'black'"}}}}}}}};
    add_mark(s, std::move(label));
  }
  return s;
}

namespace {

void outline(json& spec, const std::vector<int>& indices, bool columns, const std::string& colour,
             const std::string& label, const std::string& name) {
  const std::string scale = columns ? "x" : "y";
  json values = json::array();
  for (int i : indices) values.push_back({{"index", i}});
  add_data(spec, name + "_data", values);
  const json along = {{"scale", scale}, {"field", "index"}};
  const json across_start = {{"value", -3}};
  const json across_end = {{"signal", columns ? "height + 3" : "width + 3"}};
  json enter = {{columns ? "x" : "y", along},
                {columns ? "width" : "height", {{"scale", scale}, {"band", 1}}},
                {columns ? "y" : "x", across_start},
                {columns ? "y2" : "x2", across_end},
                {"stroke", {{"value", colour}}},
                {"strokeWidth", {{"value", 2.5}}},
                {"fillOpacity", {{"value", 0}}}};
  add_mark(spec, {{"type", "rect"}, {"name", name}, {"from", {{"data", name + "_data"}}},
                  {"encode", {{"enter", enter}}}});
  if (label.empty()) return;
  json text_enter = {{"text", {{"value", label}}},
                     {"fill", {{"value", colour}}},
                     {"fontSize", {{"value", 10}}},
                     {"fontWeight", {{"value", "bold"}}}};
  if (columns) {
    text_enter["x"] = {{"scale", "x"}, {"field", "index"}, {"band", 0.5}};
    text_enter["y"] = {{"signal", "height + 14"}};
    text_enter["align"] = {{"value", "center"}};
  } else {
    text_enter["y"] = {{"scale", "y"}, {"field", "index"}, {"band", 0.5}};
    text_enter["x"] = {{"signal", "width + 6"}};
    text_enter["baseline"] = {{"value", "middle"}};
    // the colour bar stands right of the grid: move it clear of the labels
    for (auto& l : spec["legends"])
      l["offset"] = std::max(l.value("offset", 18), 12 + 7 * static_cast<int>(label.size()));
  }
  add_mark(spec, {{"type", "text"}, {"name", name + "_label"}, {"from", {{"data", name + "_data"}}},
                  {"encode", {{"enter", text_enter}}}});
}

}  // namespace

void outline_columns(json& heat_map_spec, const std::vector<int>& columns,
                     const std::string& colour, const std::string& label, const std::string& name) {
  outline(heat_map_spec, columns, true, colour, label, name);
}

void outline_rows(json& heat_map_spec, const std::vector<int>& rows, const std::string& colour,
                  const std::string& label, const std::string& name) {
  outline(heat_map_spec, rows, false, colour, label, name);
}

}  // namespace palp::report::vega
