// SPDX-License-Identifier: Apache-2.0
// The map's section: the k_fd heat map on the grid (rows down, columns across, as the paper's
// Fig. 6b) with its colour bar and the soft and stiff lines outlined, and beside it the F_o–δ
// curves of one point, the one clicked (a Vega signal; every point's curves are embedded, as
// block means). Hovering a cell shows its values. A table lists the lines that stand out.
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <string>
#include <vector>

#include "palp/error.hpp"
#include "palp/indent.hpp"
#include "report/report_internal.hpp"
#include "report/sections.hpp"
#include "report/vega_build.hpp"

namespace palp::report {

namespace fs = std::filesystem;
using nlohmann::json;
using detail::num;

namespace {

constexpr int kCellPx = 46;             ///< a grid cell's side
constexpr int kDetailWidthPx = 380;     ///< the F_o–δ plot beside the map
constexpr int kDetailGapPx = 190;       ///< room for the row marks and the colour bar
constexpr Eigen::Index kBlocksPerRepetition = 100;  ///< block means drawn per repetition

/// A number rounded to `decimals` for the embedded data (short JSON).
double rounded(double v, int decimals) {
  const double s = std::pow(10.0, decimals);
  return std::round(v * s) / s;
}

/// What a point's result directory adds to map.json: its curves and the numbers map.json may lack.
struct PointResult {
  json curves = json::array();  ///< one entry per repetition: {row, column, rep, d: [mm], f: [N]}
  std::string why;              ///< why there are no curves
  json delta0_mm, k_tangent_N_per_mm;  ///< result.json's, null when absent
};

/// One point's F_o–δ curves, each repetition as block means of consecutive samples;
/// F_o = K_f (i - I_c) - k_v (z - z_c) with the result's own analysis parameters and contact
/// point. No curves, with `why`, when the point has none.
PointResult point_result(const MapPoint& p, const fs::path& dir, double (&range)[4]) {
  PointResult pr;
  json& out = pr.curves;
  std::string& why = pr.why;
  if (p.result_dir.empty()) {
    why = p.reason.empty() ? "not indented" : p.reason;
    return pr;
  }
  try {
    const LoadedResult r = load_result(dir / p.result_dir);
    const json& a = r.summary.value("analysis", json(nullptr));
    if (!a.is_object() || !a.value("contact_point_mm", json(nullptr)).is_number()) {
      why = "no contact point in " + p.result_dir + "/result.json";
      return pr;
    }
    pr.delta0_mm = a.value("delta0_mm", json(nullptr));
    pr.k_tangent_N_per_mm = a.value("k_tangent_N_per_mm", json(nullptr));
    const IndentationSettings s =
        indentation_settings_from_json(r.summary.at("parameters"), p.result_dir + "/result.json: parameters.");
    const double zc_m = a["contact_point_mm"].get<double>() * 1e-3;
    const analysis::Curve c = curve_of(r.recordings.at(0).second);
    const Eigen::VectorXd Fo = analysis::object_force_N(c, s.analysis, zc_m);
    for (Eigen::Index b = 0; b < c.z_m.size();) {
      Eigen::Index e = b;
      while (e < c.z_m.size() && (c.rep.size() == 0 || c.rep[e] == c.rep[b])) ++e;
      const Eigen::Index n = e - b, block = std::max<Eigen::Index>(1, (n + kBlocksPerRepetition - 1) / kBlocksPerRepetition);
      json d = json::array(), f = json::array();
      for (Eigen::Index k = b; k < e; k += block) {
        const Eigen::Index m = std::min(block, e - k);
        const double dm = (c.z_m.segment(k, m).mean() - zc_m) * 1e3, fm = Fo.segment(k, m).mean();
        d.push_back(rounded(dm, 4));
        f.push_back(rounded(fm, 4));
        range[0] = std::min(range[0], dm);
        range[1] = std::max(range[1], dm);
        range[2] = std::min(range[2], fm);
        range[3] = std::max(range[3], fm);
      }
      const int rep = (c.rep.size() == 0 ? 0 : c.rep[b]) + 1;  // 1-based, as the tables say
      out.push_back({{"row", p.row}, {"column", p.column}, {"rep", rep}, {"d", d}, {"f", f}});
      b = e;
    }
  } catch (const Error& e) {
    why = e.what();
    out = json::array();
  }
  return pr;
}

/// map.json's value in lab units, else result.json's (a number or null).
json value_or(const std::optional<double>& v, double scale, const json& from_result) {
  if (v) return rounded(*v * scale, 4);
  return from_result.is_number() ? json(rounded(from_result.get<double>(), 4)) : json(nullptr);
}

std::string lines_text(const std::vector<int>& v) {
  if (v.empty()) return "none";
  std::string s;
  for (const int x : v) s += (s.empty() ? "" : ", ") + std::to_string(x);
  return s;
}

/// The points an irregular (adaptive) map did not measure, as cells whose value is interpolated
/// from the measured points with a value within kInterpolationRadius grid steps (Chebyshev):
/// inverse-distance weights 1 / d^2, a weighted mean, so never beyond the measured values around
/// it; none within the radius: no value (grey). Marked "measured": false. Returns how many got a
/// value.
constexpr int kInterpolationRadius = 2;
std::size_t add_interpolated_cells(const StiffnessMap& map, const MapAnalysis& a,
                                   std::vector<vega::HeatCell>& cells) {
  std::size_t with_value = 0;
  for (int r = 1; r <= map.rows; ++r)
    for (int c = 1; c <= map.columns; ++c) {
      const std::size_t at = static_cast<std::size_t>((r - 1) * map.columns + (c - 1));
      if (at >= a.measured.size() || a.measured[at]) continue;
      double sum = 0, weights = 0;
      int from = 0;
      for (int rr = std::max(1, r - kInterpolationRadius);
           rr <= std::min(map.rows, r + kInterpolationRadius); ++rr)
        for (int cc = std::max(1, c - kInterpolationRadius);
             cc <= std::min(map.columns, c + kInterpolationRadius); ++cc) {
          const auto& k = a.k_N_per_m[static_cast<std::size_t>((rr - 1) * map.columns + (cc - 1))];
          if (!k) continue;
          const double w = 1.0 / ((rr - r) * (rr - r) + (cc - c) * (cc - c));
          sum += w * *k * 1e-3;
          weights += w;
          ++from;
        }
      vega::HeatCell cell;
      cell.row = r;
      cell.column = c;
      cell.value = from > 0 ? rounded(sum / weights, 4) : NAN;
      with_value += from > 0 ? 1 : 0;
      const std::string radius = std::to_string(kInterpolationRadius) + " grid steps";
      cell.extra = {
          {"delta0", nullptr},
          {"kt", nullptr},
          {"reason", from > 0 ? "not measured: interpolated from the " + std::to_string(from) +
                                    " measured points within " + radius + " (inverse-distance)"
                              : "not measured; no measured point within " + radius},
          {"measured", false}};
      cells.push_back(std::move(cell));
    }
  return with_value;
}

/// What an irregular (adaptive) map measured, for the section's text ("" for a whole grid).
std::string adaptive_text(const StiffnessMap& map, std::size_t interpolated) {
  const std::size_t grid = static_cast<std::size_t>(map.rows * map.columns);
  if (map.points.size() >= grid) return "";
  std::string s = " (" + std::to_string(map.points.size()) + " of the " + std::to_string(grid) +
                  " points measured";
  if (map.adaptive)
    s += " by the adaptive map: a coarse design of " + std::to_string(map.adaptive->coarse_points) +
         " points, then refinement where neighbours differ by more than " +
         num(map.adaptive->threshold * 100) + " %, budget " +
         std::to_string(map.adaptive->max_points);
  return s + "; a dot marks each measured cell, the " + std::to_string(interpolated) +
         " pale cells with values in parentheses are interpolated between them and take no part in "
         "the means)";
}

}  // namespace

Section map_section(const StiffnessMap& map, const MapAnalysis& analysis, const fs::path& dir) {
  if (map.rows <= 0 || map.columns <= 0 || analysis.rows != map.rows || analysis.columns != map.columns)
    throw ConfigError(dir.string() + ": the map's grid is " + std::to_string(map.rows) + " x " +
                      std::to_string(map.columns) + " and its analysis' " + std::to_string(analysis.rows) + " x " +
                      std::to_string(analysis.columns) + "; nothing to draw");
  const int W = map.columns * kCellPx, H = map.rows * kCellPx;  // the grid's size in pixels

  // the cells (k_fd and the point's other values), their curves
  std::vector<vega::HeatCell> cells;
  json curves = json::array();
  double range[4] = {0, 0, 0, 0};  // δ min, max (mm), F_o min, max (N): the detail plot's axes
  const MapPoint* first_with_curves = nullptr;
  for (const MapPoint& p : map.points) {
    if (p.row < 1 || p.row > map.rows || p.column < 1 || p.column > map.columns) continue;
    const std::size_t at = static_cast<std::size_t>((p.row - 1) * map.columns + (p.column - 1));
    // k in N/mm, NaN where the point has none
    const double k = at < analysis.k_N_per_m.size() ? analysis.k_N_per_m[at].value_or(NAN) * 1e-3 : NAN;
    const PointResult pr = point_result(p, dir, range);
    for (const json& rep : pr.curves) curves.push_back(rep);
    if (!pr.curves.empty() && first_with_curves == nullptr) first_with_curves = &p;
    std::string reason = p.reason;
    if (std::isnan(k) && !p.k_fd_reason.empty()) reason += (reason.empty() ? "" : "; ") + p.k_fd_reason;
    if (!pr.why.empty()) reason += (reason.empty() ? "" : "; ") + ("curves: " + pr.why);
    vega::HeatCell c;
    c.row = p.row;
    c.column = p.column;
    c.value = std::isnan(k) ? NAN : rounded(k, 4);
    c.extra = {{"delta0", value_or(p.delta0_m, 1e3, pr.delta0_mm)},
               {"kt", value_or(p.k_tangent_N_per_m, 1e-3, pr.k_tangent_N_per_mm)},
               {"reason", reason.empty() ? "–" : reason},
               {"measured", true}};
    cells.push_back(std::move(c));
  }
  const std::size_t interpolated = add_interpolated_cells(map, analysis, cells);
  const int sel_row = first_with_curves ? first_with_curves->row : 1;
  const int sel_column = first_with_curves ? first_with_curves->column : 1;
  const double lo_mm = map.settings.analysis.window_lo_m * 1e3, hi_mm = map.settings.analysis.window_hi_m * 1e3;

  // the heat map (vega_build): rows down, columns across, the colour bar right of it; the soft
  // lines outlined in red, the stiff ones in black
  vega::HeatMapStyle style;
  style.cell_px = kCellPx;
  style.value_title = "k_fd (N/mm)";
  style.format = ".2f";
  json spec = vega::heat_map(map.rows, map.columns, cells, style);
  constexpr const char* kSoft = "#D55E00";
  constexpr const char* kStiff = "#000000";
  vega::outline_columns(spec, analysis.soft_columns, kSoft, "soft", "soft_columns");
  vega::outline_columns(spec, analysis.stiff_columns, kStiff, "stiff", "stiff_columns");
  vega::outline_rows(spec, analysis.soft_rows, kSoft, "soft", "soft_rows");
  vega::outline_rows(spec, analysis.stiff_rows, kStiff, "stiff", "stiff_rows");
  // the colour bar right of the grid (and of the rows' labels), not right of the detail plot
  for (json& l : spec["legends"]) {
    l["legendX"] = W + l.value("offset", 18);
    l["legendY"] = 0;
    l["orient"] = "none";
  }
  spec["description"] = "k_fd heat map of a stiffness map, and the F_o–δ curves of the point selected";
  // hover: every value of the point; click: select it (its curves drawn on the right)
  for (json& m : spec["marks"]) {
    if (m.value("name", "") != "heat_cells") continue;
    m["encode"]["enter"]["cursor"] = {{"value", "pointer"}};
    m["encode"]["enter"]["tooltip"] = {
        {"signal",
         "{'point': 'row ' + datum.row + ', column ' + datum.column, "
         "'k_fd (N/mm)': isValid(datum.value) ? format(datum.value, '.3f') : '–', "
         "'δ0 (mm)': isValid(datum.delta0) ? format(datum.delta0, '.3f') : '–', "
         "'k_tangent (N/mm)': isValid(datum.kt) ? format(datum.kt, '.3f') : '–', "
         "'reason': datum.reason}"}};
    m["encode"]["enter"]["fillOpacity"] = {
        {"signal", "datum.measured === false ? 0.45 : 1"}};  // interpolated: pale
  }
  for (json& m : spec["marks"])
    if (m.value("name", "") == "cell_labels") {
      m["encode"]["enter"]["text"] = {
          {"signal",
           "!isValid(datum.value) ? '–' : datum.measured === false ? '(' + "
           "format(datum.value, '.2f') + ')' : format(datum.value, '.2f')"}};
      m["encode"]["enter"]["fill"] = {
          {"signal",
           "datum.measured === false ? '#333333' : datum.shade < 0.55 ? 'white' : 'black'"}};
    }
  if (map.points.size() < static_cast<std::size_t>(map.rows * map.columns)) {
    // a dot in the corner of every measured cell
    spec["data"].push_back(
        {{"name", "measured_cells"},
         {"source", "cells"},
         {"transform", json::array({{{"type", "filter"}, {"expr", "datum.measured === true"}}})}});
    vega::add_mark(spec, {{"type", "symbol"},
                          {"name", "measured_marks"},
                          {"from", {{"data", "measured_cells"}}},
                          {"interactive", false},
                          {"encode",
                           {{"enter",
                             {{"x", {{"scale", "x"}, {"field", "column"}, {"band", 0.84}}},
                              {"y", {{"scale", "y"}, {"field", "row"}, {"band", 0.16}}},
                              {"shape", {{"value", "circle"}}},
                              {"size", {{"value", 24}}},
                              {"fill", {{"value", "#000000"}}},
                              {"stroke", {{"value", "#ffffff"}}},
                              {"strokeWidth", {{"value", 1}}}}}}}});
  }
  spec["signals"] = json::array({{{"name", "selected"},
                                  {"value", {{"row", sel_row}, {"column", sel_column}}},
                                  {"on", json::array({{{"events", "@heat_cells:click"},
                                                       {"update", "{row: datum.row, column: datum.column}"}}})}}});
  const std::string is_selected = "datum.row === selected.row && datum.column === selected.column";
  vega::add_data(spec, "curves", curves);
  spec["data"].push_back({{"name", "selected_cell"},
                          {"source", "cells"},
                          {"transform", json::array({{{"type", "filter"}, {"expr", is_selected}}})}});
  spec["data"].push_back({{"name", "detail"},
                          {"source", "curves"},
                          {"transform", json::array({{{"type", "filter"}, {"expr", is_selected}},
                                                     {{"type", "flatten"}, {"fields", json::array({"d", "f"})}}})}});
  vega::add_mark(spec, {{"type", "rect"},
                        {"name", "selected_outline"},
                        {"from", {{"data", "selected_cell"}}},
                        {"interactive", false},
                        {"encode",
                         {{"update",
                           {{"x", {{"scale", "x"}, {"field", "column"}}},
                            {"width", {{"scale", "x"}, {"band", 1}}},
                            {"y", {{"scale", "y"}, {"field", "row"}}},
                            {"height", {{"scale", "y"}, {"band", 1}}},
                            {"fillOpacity", {{"value", 0}}},
                            {"stroke", {{"value", "#000000"}}},
                            {"strokeWidth", {{"value", 3.5}}}}}}}});

  // the selected point's curves, beside the map (its own scales, over every point's curves so
  // that points compare; the top-level width stays the grid's, which the outlines use)
  json rep_domain = json::array();
  for (const json& c : curves)
    if (std::find(rep_domain.begin(), rep_domain.end(), c["rep"]) == rep_domain.end()) rep_domain.push_back(c["rep"]);
  std::sort(rep_domain.begin(), rep_domain.end());
  json rep_colours = json::array();
  for (std::size_t i = 0; i < rep_domain.size(); ++i) rep_colours.push_back(vega::colour(static_cast<int>(i)));
  json detail = {
      {"type", "group"},
      {"name", "point_detail"},
      {"encode",
       {{"enter",
         {{"x", {{"value", W + kDetailGapPx}}},
          {"y", {{"value", 0}}},
          {"width", {{"value", kDetailWidthPx}}},
          {"height", {{"value", H}}}}}}},
      {"title",
       {{"text", {{"signal", "'F_o–δ at row ' + selected.row + ', column ' + selected.column"}}}, {"fontSize", 12}}},
      {"scales",
       json::array({{{"name", "dx"},
                     {"type", "linear"},
                     {"domain", json::array({rounded(range[0], 3), rounded(std::max(range[1], hi_mm), 3)})},
                     {"range", json::array({0, kDetailWidthPx})},
                     {"nice", true},
                     {"zero", false}},
                    {{"name", "dy"},
                     {"type", "linear"},
                     {"domain", json::array({rounded(range[2], 3), rounded(range[3], 3)})},
                     {"range", json::array({H, 0})},
                     {"nice", true},
                     {"zero", true}},
                    {{"name", "rep_colour"}, {"type", "ordinal"}, {"domain", rep_domain}, {"range", rep_colours}}})},
      {"axes", json::array({vega::axis("dx", "bottom", "δ (mm)"), vega::axis("dy", "left", "F_o (N)")})},
      {"legends", json::array({vega::legend("rep_colour", "repetition", "bottom-right")})},
      {"marks",
       json::array(
           {{{"type", "rect"},
             {"name", "kfd_window"},
             {"interactive", false},
             {"encode",
              {{"enter",
                {{"x", {{"scale", "dx"}, {"value", lo_mm}}},
                 {"x2", {{"scale", "dx"}, {"value", hi_mm}}},
                 {"y", {{"value", 0}}},
                 {"y2", {{"value", H}}},
                 {"fill", {{"value", "#9fb7d9"}}},
                 {"opacity", {{"value", 0.25}}}}}}}},
            {{"type", "group"},
             {"name", "repetitions"},
             {"from", {{"facet", {{"name", "rep_curve"}, {"data", "detail"}, {"groupby", "rep"}}}}},
             {"marks",
              json::array({{{"type", "line"},
                            {"name", "curve"},
                            {"from", {{"data", "rep_curve"}}},
                            {"encode",
                             {{"update",
                               {{"x", {{"scale", "dx"}, {"field", "d"}}},
                                {"y", {{"scale", "dy"}, {"field", "f"}}},
                                {"stroke", {{"scale", "rep_colour"}, {"field", "rep"}}},
                                {"strokeWidth", {{"value", 1.6}}}}}}}}})}}})}};
  vega::add_mark(spec, std::move(detail));

  Section s;
  s.id = "map";
  s.title = "Stiffness map";
  std::size_t present = 0;
  for (const auto& k : analysis.k_N_per_m) present += k ? 1 : 0;
  s.text = "k_fd = (F_o(" + num(hi_mm) + " mm) − F_o(" + num(lo_mm) + " mm)) / " +
           num(hi_mm - lo_mm) + " mm at each point of the " + std::to_string(map.rows) + " × " +
           std::to_string(map.columns) + " grid (the paper's Fig. 6b), " + std::to_string(present) +
           " of " + std::to_string(analysis.k_N_per_m.size()) + " points with a value" +
           adaptive_text(map, interpolated) + "; median " + num(analysis.median_N_per_m * 1e-3) +
           " N/mm. A column or row is soft (stiff) when its mean is at least " +
           num(analysis.contrast * 100) +
           " % below (above) the median of the columns' (rows') means. Soft columns: " +
           lines_text(analysis.soft_columns) +
           "; stiff columns: " + lines_text(analysis.stiff_columns) +
           "; soft rows: " + lines_text(analysis.soft_rows) +
           "; stiff rows: " + lines_text(analysis.stiff_rows) + ".";

  Figure f;
  f.id = "map-stiffness";
  f.title = "k_fd heat map and one point's force–depth curves";
  f.caption =
      "Left: k_fd per grid point (N/mm; grey: no value), rows down and columns across; on a map "
      "that measured only some points a dot marks each measured one, and the pale cells with "
      "values in parentheses are interpolated from the measured points within " +
      std::to_string(kInterpolationRadius) +
      " grid steps (inverse-distance weights); soft lines outlined in vermilion, stiff ones in "
      "black; the black square is the point drawn on the right. In the page, hover a cell for its "
      "k_fd, δ0, tangent stiffness and any reason, and click it to draw its curves. Right: F_o "
      "against δ = z − z_c of every repetition (" +
      std::to_string(kBlocksPerRepetition) + " block means each), the k_fd window " + num(lo_mm) +
      "–" + num(hi_mm) + " mm shaded.";
  f.spec = std::move(spec);
  s.figures.push_back(std::move(f));

  Table t;
  t.id = "map-lines";
  t.title = "Mean k_fd of every column and row";
  t.columns = {"line", "mean k_fd (N/mm)", "vs. median of the means (%)", "marked"};
  const auto add_lines = [&](const char* kind, const std::vector<double>& means, const std::vector<int>& soft,
                             const std::vector<int>& stiff) {
    std::vector<double> sorted = means;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t n = sorted.size();
    const double median = n == 0 ? 0.0 : n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    for (std::size_t i = 0; i < means.size(); ++i) {
      const int index = static_cast<int>(i) + 1;
      const bool is_soft = std::find(soft.begin(), soft.end(), index) != soft.end();
      const bool is_stiff = std::find(stiff.begin(), stiff.end(), index) != stiff.end();
      t.rows.push_back({std::string(kind) + " " + std::to_string(index), detail::fixed(means[i] * 1e-3, 3),
                        median > 0 ? detail::fixed(100.0 * (means[i] / median - 1.0), 1, true) : "–",
                        is_soft ? "soft" : is_stiff ? "stiff" : ""});
    }
  };
  add_lines("column", analysis.column_mean_N_per_m, analysis.soft_columns, analysis.stiff_columns);
  add_lines("row", analysis.row_mean_N_per_m, analysis.soft_rows, analysis.stiff_rows);
  const std::vector<bool>& seen = analysis.measured;
  const bool fitted = map.adaptive && std::find(seen.begin(), seen.end(), false) != seen.end();
  t.caption = std::string(fitted ? "Means over the measured points with a value (points not "
                                   "measured: each line's mean from an additive row + column fit, "
                                   "which the sampling does not bias)"
                                 : "Means over the points with a value") +
              "; a line is marked when it is at least " + num(analysis.contrast * 100) +
              " % below (soft) or above (stiff) the median of its kind's means.";
  s.tables.push_back(std::move(t));
  return s;
}

}  // namespace palp::report
