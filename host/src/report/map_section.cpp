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

namespace palp::report {

namespace fs = std::filesystem;
using nlohmann::json;
using detail::num;

namespace {

constexpr int kCellPx = 46;             ///< a grid cell's side
constexpr int kDetailWidthPx = 380;     ///< the F_o–δ plot beside the map
constexpr int kDetailGapPx = 180;       ///< room for the row marks and the colour bar
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
      out.push_back({{"row", p.row}, {"column", p.column}, {"rep", c.rep.size() == 0 ? 0 : c.rep[b]}, {"d", d}, {"f", f}});
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

json axis(const char* scale, const char* orient, const std::string& title, json extra = json::object()) {
  json a = {{"scale", scale}, {"orient", orient}, {"title", title}, {"titleFontSize", 13}, {"labelFontSize", 11}};
  a.update(extra);
  return a;
}

}  // namespace

Section map_section(const StiffnessMap& map, const MapAnalysis& analysis, const fs::path& dir) {
  if (map.rows <= 0 || map.columns <= 0 || analysis.rows != map.rows || analysis.columns != map.columns)
    throw ConfigError(dir.string() + ": the map's grid is " + std::to_string(map.rows) + " x " +
                      std::to_string(map.columns) + " and its analysis' " + std::to_string(analysis.rows) + " x " +
                      std::to_string(analysis.columns) + "; nothing to draw");
  const int W = map.columns * kCellPx, H = map.rows * kCellPx;

  // the points, their curves, the lines that stand out
  json points = json::array(), curves = json::array(), lines = json::array();
  double range[4] = {0, 0, 0, 0};  // δ min, max (mm), F_o min, max (N): the detail plot's axes
  double kmin = std::numeric_limits<double>::infinity(), kmax = -kmin;
  const MapPoint* first_with_curves = nullptr;
  for (const MapPoint& p : map.points) {
    if (p.row < 1 || p.row > map.rows || p.column < 1 || p.column > map.columns) continue;
    const std::size_t at = static_cast<std::size_t>((p.row - 1) * map.columns + (p.column - 1));
    // k in N/mm, NaN where the point has none
    const double k = at < analysis.k_N_per_m.size() ? analysis.k_N_per_m[at].value_or(NAN) * 1e-3 : NAN;
    const PointResult pr = point_result(p, dir, range);
    const json& c = pr.curves;
    const std::string& why = pr.why;
    for (const json& rep : c) curves.push_back(rep);
    if (!c.empty() && first_with_curves == nullptr) first_with_curves = &p;
    std::string reason = p.reason;
    if (std::isnan(k) && !p.k_fd_reason.empty()) reason += (reason.empty() ? "" : "; ") + p.k_fd_reason;
    if (!why.empty()) reason += (reason.empty() ? "" : "; ") + ("curves: " + why);
    if (!std::isnan(k)) {
      kmin = std::min(kmin, k);
      kmax = std::max(kmax, k);
    }
    points.push_back({{"row", p.row},
                      {"column", p.column},
                      {"k", std::isnan(k) ? json(nullptr) : json(rounded(k, 4))},
                      {"delta0", value_or(p.delta0_m, 1e3, pr.delta0_mm)},
                      {"kt", value_or(p.k_tangent_N_per_m, 1e-3, pr.k_tangent_N_per_mm)},
                      {"reason", reason.empty() ? "–" : reason}});
  }
  for (const auto& [kind, label, v] : {std::tuple{"column", "soft", &analysis.soft_columns},
                                       std::tuple{"column", "stiff", &analysis.stiff_columns},
                                       std::tuple{"row", "soft", &analysis.soft_rows},
                                       std::tuple{"row", "stiff", &analysis.stiff_rows}})
    for (const int index : *v) lines.push_back({{"kind", kind}, {"label", label}, {"index", index}});
  const bool any_k = std::isfinite(kmin);
  const double kmid = any_k ? 0.5 * (kmin + kmax) : 0.0;
  const int sel_row = first_with_curves ? first_with_curves->row : 1;
  const int sel_column = first_with_curves ? first_with_curves->column : 1;
  json row_domain = json::array(), column_domain = json::array();
  for (int r = 1; r <= map.rows; ++r) row_domain.push_back(r);
  for (int c = 1; c <= map.columns; ++c) column_domain.push_back(c);
  const double lo_mm = map.settings.analysis.window_lo_m * 1e3, hi_mm = map.settings.analysis.window_hi_m * 1e3;

  const json line_stroke = {{"signal", "datum.label === 'soft' ? '#e8402f' : '#111111'"}};
  json heat_marks = json::array({
      {{"type", "rect"},
       {"name", "cell"},
       {"from", {{"data", "points"}}},
       {"encode",
        {{"enter",
          {{"x", {{"scale", "x"}, {"field", "column"}}},
           {"width", {{"scale", "x"}, {"band", 1}}},
           {"y", {{"scale", "y"}, {"field", "row"}}},
           {"height", {{"scale", "y"}, {"band", 1}}},
           {"stroke", {{"value", "#ffffff"}}},
           {"strokeWidth", {{"value", 1}}},
           {"cursor", {{"value", "pointer"}}},
           {"tooltip",
            {{"signal",
              "{'point': 'row ' + datum.row + ', column ' + datum.column, "
              "'k_fd (N/mm)': datum.k === null ? '–' : format(datum.k, '.3f'), "
              "'δ0 (mm)': datum.delta0 === null ? '–' : format(datum.delta0, '.3f'), "
              "'k_tangent (N/mm)': datum.kt === null ? '–' : format(datum.kt, '.3f'), "
              "'reason': datum.reason}"}}}}},
         {"update",
          {{"fill", json::array({{{"test", "datum.k === null"}, {"value", "#d4d4d4"}}, {{"scale", "color"}, {"field", "k"}}})},
           {"opacity", json::array({{{"test", "hoverRow === datum.row && hoverColumn === datum.column"}, {"value", 0.8}},
                                    {{"value", 1}}})}}}}}},
      {{"type", "text"},
       {"name", "cell-value"},
       {"from", {{"data", "points"}}},
       {"interactive", false},
       {"encode",
        {{"enter",
          {{"x", {{"scale", "x"}, {"field", "column"}, {"band", 0.5}}},
           {"y", {{"scale", "y"}, {"field", "row"}, {"band", 0.5}}},
           {"align", {{"value", "center"}}},
           {"baseline", {{"value", "middle"}}},
           {"fontSize", {{"value", 10.5}}},
           {"text", {{"signal", "datum.k === null ? '–' : format(datum.k, '.2f')"}}},
           {"fill", {{"signal", "datum.k !== null && datum.k < " + num(kmid, 6) + " ? '#ffffff' : '#111111'"}}}}}}}},
      {{"type", "rect"},
       {"name", "marked-column"},
       {"from", {{"data", "marked_columns"}}},
       {"interactive", false},
       {"encode",
        {{"enter",
          {{"x", {{"scale", "x"}, {"field", "index"}}},
           {"width", {{"scale", "x"}, {"band", 1}}},
           {"y", {{"value", 0}}},
           {"y2", {{"signal", "height"}}},
           {"fill", {{"value", "transparent"}}},
           {"stroke", line_stroke},
           {"strokeWidth", {{"value", 2.5}}},
           {"strokeDash", {{"signal", "datum.label === 'soft' ? [] : [6, 3]"}}}}}}}},
      {{"type", "text"},
       {"name", "marked-column-label"},
       {"from", {{"data", "marked_columns"}}},
       {"interactive", false},
       {"encode",
        {{"enter",
          {{"x", {{"scale", "x"}, {"field", "index"}, {"band", 0.5}}},
           {"y", {{"value", -6}}},
           {"align", {{"value", "center"}}},
           {"fontSize", {{"value", 11}}},
           {"fontWeight", {{"value", "bold"}}},
           {"fill", line_stroke},
           {"text", {{"field", "label"}}}}}}}},
      {{"type", "rect"},
       {"name", "marked-row"},
       {"from", {{"data", "marked_rows"}}},
       {"interactive", false},
       {"encode",
        {{"enter",
          {{"y", {{"scale", "y"}, {"field", "index"}}},
           {"height", {{"scale", "y"}, {"band", 1}}},
           {"x", {{"value", 0}}},
           {"x2", {{"signal", "width"}}},
           {"fill", {{"value", "transparent"}}},
           {"stroke", line_stroke},
           {"strokeWidth", {{"value", 2.5}}},
           {"strokeDash", {{"signal", "datum.label === 'soft' ? [] : [6, 3]"}}}}}}}},
      {{"type", "text"},
       {"name", "marked-row-label"},
       {"from", {{"data", "marked_rows"}}},
       {"interactive", false},
       {"encode",
        {{"enter",
          {{"y", {{"scale", "y"}, {"field", "index"}, {"band", 0.5}}},
           {"x", {{"signal", "width + 5"}}},
           {"baseline", {{"value", "middle"}}},
           {"fontSize", {{"value", 11}}},
           {"fontWeight", {{"value", "bold"}}},
           {"fill", line_stroke},
           {"text", {{"field", "label"}}}}}}}},
      {{"type", "rect"},
       {"name", "selected-cell"},
       {"from", {{"data", "selected_point"}}},
       {"interactive", false},
       {"encode",
        {{"update",
          {{"x", {{"scale", "x"}, {"field", "column"}}},
           {"width", {{"scale", "x"}, {"band", 1}}},
           {"y", {{"scale", "y"}, {"field", "row"}}},
           {"height", {{"scale", "y"}, {"band", 1}}},
           {"fill", {{"value", "transparent"}}},
           {"stroke", {{"value", "#000000"}}},
           {"strokeWidth", {{"value", 3.5}}}}}}}},
  });

  json heat = {
      {"type", "group"},
      {"name", "heat-map"},
      {"encode", {{"enter", {{"x", {{"value", 0}}}, {"y", {{"value", 0}}}, {"width", {{"value", W}}}, {"height", {{"value", H}}}}}}},
      {"title", {{"text", "k_fd per grid point"}, {"offset", 18}, {"fontSize", 13}}},
      {"axes", json::array({axis("x", "bottom", "column", {{"domain", false}, {"ticks", false}}),
                            axis("y", "left", "row", {{"domain", false}, {"ticks", false}})})},
      {"legends", json::array({{{"fill", "color"},
                                {"type", "gradient"},
                                {"title", "k_fd (N/mm)"},
                                {"orient", "right"},
                                {"offset", 44},
                                {"gradientLength", std::max(80, H - 30)},
                                {"titleFontSize", 12},
                                {"labelFontSize", 11},
                                {"format", ".2f"}}})},
      {"marks", heat_marks}};

  json detail = {
      {"type", "group"},
      {"name", "point-detail"},
      {"encode",
       {{"enter",
         {{"x", {{"value", W + kDetailGapPx}}},
          {"y", {{"value", 0}}},
          {"width", {{"value", kDetailWidthPx}}},
          {"height", {{"value", H}}}}}}},
      {"title",
       {{"text", {{"signal", "'F_o–δ at row ' + selected.row + ', column ' + selected.column"}}},
        {"offset", 18},
        {"fontSize", 13}}},
      {"axes", json::array({axis("dx", "bottom", "δ (mm)", {{"grid", true}, {"gridOpacity", 0.35}}),
                            axis("dy", "left", "F_o (N)", {{"grid", true}, {"gridOpacity", 0.35}})})},
      {"legends", json::array({{{"stroke", "rep_colour"},
                                {"title", "repetition"},
                                {"symbolType", "stroke"},
                                {"orient", "bottom-right"},
                                {"offset", 6},
                                {"fillColor", "rgba(255,255,255,0.85)"},
                                {"padding", 4}}})},
      {"marks",
       json::array(
           {{{"type", "rect"},
             {"name", "kfd-window"},
             {"interactive", false},
             {"encode",
              {{"enter",
                {{"x", {{"scale", "dx"}, {"value", lo_mm}}},
                 {"x2", {{"scale", "dx"}, {"value", hi_mm}}},
                 {"y", {{"value", 0}}},
                 {"y2", {{"signal", "height"}}},
                 {"fill", {{"value", "#9fb7d9"}}},
                 {"opacity", {{"value", 0.25}}}}}}}},
            {{"type", "group"},
             {"name", "repetition"},
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

  json spec = {
      {"$schema", "https://vega.github.io/schema/vega/v5.json"},
      {"description", "k_fd heat map of a stiffness map, and one point's F_o–δ curves"},
      {"width", W + kDetailGapPx + kDetailWidthPx},
      {"height", H},
      {"padding", {{"left", 8}, {"right", 12}, {"top", 8}, {"bottom", 8}}},
      {"autosize", {{"type", "pad"}}},
      {"background", "#ffffff"},
      {"config", {{"text", {{"font", "DejaVu Sans, Helvetica, Arial, sans-serif"}}},
                  {"axis", {{"labelFont", "DejaVu Sans, Helvetica, Arial, sans-serif"},
                            {"titleFont", "DejaVu Sans, Helvetica, Arial, sans-serif"}}},
                  {"legend", {{"labelFont", "DejaVu Sans, Helvetica, Arial, sans-serif"},
                              {"titleFont", "DejaVu Sans, Helvetica, Arial, sans-serif"}}},
                  {"title", {{"font", "DejaVu Sans, Helvetica, Arial, sans-serif"}}}}},
      {"signals",
       json::array({{{"name", "selected"},
                     {"value", {{"row", sel_row}, {"column", sel_column}}},
                     {"on", json::array({{{"events", "@cell:click"},
                                          {"update", "{row: datum.row, column: datum.column}"}}})}},
                    {{"name", "hoverRow"},
                     {"value", 0},
                     {"on", json::array({{{"events", "@cell:mouseover"}, {"update", "datum.row"}},
                                         {{"events", "@cell:mouseout"}, {"update", "0"}}})}},
                    {{"name", "hoverColumn"},
                     {"value", 0},
                     {"on", json::array({{{"events", "@cell:mouseover"}, {"update", "datum.column"}},
                                         {{"events", "@cell:mouseout"}, {"update", "0"}}})}}})},
      {"data",
       json::array({{{"name", "points"}, {"values", points}},
                    {{"name", "lines"}, {"values", lines}},
                    {{"name", "marked_columns"},
                     {"source", "lines"},
                     {"transform", json::array({{{"type", "filter"}, {"expr", "datum.kind === 'column'"}}})}},
                    {{"name", "marked_rows"},
                     {"source", "lines"},
                     {"transform", json::array({{{"type", "filter"}, {"expr", "datum.kind === 'row'"}}})}},
                    {{"name", "selected_point"},
                     {"source", "points"},
                     {"transform",
                      json::array({{{"type", "filter"},
                                    {"expr", "datum.row === selected.row && datum.column === selected.column"}}})}},
                    {{"name", "curves"}, {"values", curves}},
                    {{"name", "detail"},
                     {"source", "curves"},
                     {"transform",
                      json::array({{{"type", "filter"},
                                    {"expr", "datum.row === selected.row && datum.column === selected.column"}},
                                   {{"type", "flatten"}, {"fields", json::array({"d", "f"})}}})}}})},
      {"scales",
       json::array({{{"name", "x"}, {"type", "band"}, {"domain", column_domain}, {"range", json::array({0, W})}},
                    {{"name", "y"}, {"type", "band"}, {"domain", row_domain}, {"range", json::array({0, H})}},
                    {{"name", "color"},
                     {"type", "linear"},
                     {"domain", any_k ? json::array({rounded(kmin, 4), rounded(kmax, 4)}) : json::array({0, 1})},
                     {"range", {{"scheme", "viridis"}}},
                     {"zero", false}},
                    {{"name", "dx"},
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
                    {{"name", "rep_colour"},
                     {"type", "ordinal"},
                     {"domain", {{"data", "curves"}, {"field", "rep"}, {"sort", true}}},
                     {"range", {{"scheme", "tableau10"}}}}})},
      {"marks", json::array({heat, detail})}};

  Section s;
  s.id = "map";
  s.title = "Stiffness map";
  std::size_t present = 0;
  for (const auto& k : analysis.k_N_per_m) present += k ? 1 : 0;
  s.text = "k_fd = (F_o(" + num(hi_mm) + " mm) − F_o(" + num(lo_mm) + " mm)) / " + num(hi_mm - lo_mm) +
           " mm at each point of the " + std::to_string(map.rows) + " × " + std::to_string(map.columns) +
           " grid (the paper's Fig. 6b), " + std::to_string(present) + " of " +
           std::to_string(analysis.k_N_per_m.size()) + " points with a value; median " +
           num(analysis.median_N_per_m * 1e-3) + " N/mm. A column or row is soft (stiff) when its mean is at least " +
           num(analysis.contrast * 100) + " % below (above) the median of the columns' (rows') means. Soft columns: " +
           lines_text(analysis.soft_columns) + "; stiff columns: " + lines_text(analysis.stiff_columns) +
           "; soft rows: " + lines_text(analysis.soft_rows) + "; stiff rows: " + lines_text(analysis.stiff_rows) + ".";

  Figure f;
  f.id = "map-stiffness";
  f.title = "k_fd heat map and one point's force–depth curves";
  f.caption = "Left: k_fd per grid point (N/mm; grey: no value), rows down and columns across; soft lines outlined "
              "in red, stiff ones dashed black; the black square is the point drawn on the right. In the page, "
              "hover a cell for its k_fd, δ0, tangent stiffness and any reason, and click it to draw its curves. "
              "Right: F_o against δ = z − z_c of every repetition (" +
              std::to_string(kBlocksPerRepetition) + " block means each), the k_fd window " + num(lo_mm) + "–" +
              num(hi_mm) + " mm shaded.";
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
  t.caption = "Means over the points with a value; a line is marked when it is at least " +
              num(analysis.contrast * 100) + " % below (soft) or above (stiff) the median of its kind's means.";
  s.tables.push_back(std::move(t));
  return s;
}

}  // namespace palp::report
