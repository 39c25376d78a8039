// SPDX-License-Identifier: Apache-2.0
// Trace files: a TracedSurface as JSON in lab units (docs/rig-and-plan.md "Trace files").
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "palp/error.hpp"
#include "palp/trace.hpp"
#include "format/field_table.hpp"
#include "format/text_input.hpp"
#include "trace_json.hpp"

namespace palp {

namespace {

using nlohmann::json;
using format::Field;
using format::Need;

// a point's measured part (read back; finish_surface derives the rest again) and, written only,
// the derived scalars
const Field<TracePoint> kTracePointFields[] = {
    {"detection_force_N", &TracePoint::detection_force_N},
    {"contact_stiffness_N_per_mm", &TracePoint::contact_stiffness_N_per_m, format::kNPerMm, Need::optional},
    {"overtravel_mm", &TracePoint::overtravel_m, format::kMm},
    {"guard_fired", &TracePoint::guard_fired},
    {"tcp_at_rest_mm_deg", &TracePoint::tcp_at_rest},
    {"stroke_at_rest_mm", &TracePoint::stroke_at_rest_m, format::kMm},
    {"tilt_deg", &TracePoint::tilt_rad, format::kDeg, Need::written},
    {"indentation_mm", &TracePoint::indentation_m, format::kMm, Need::written},
};

const Field<TracedSurface> kSurfaceFields[] = {
    {"plan", &TracedSurface::plan_name, 1.0, Need::optional},
    {"rows", &TracedSurface::rows},
    {"columns", &TracedSurface::columns},
    {"work_object_mm_deg", &TracedSurface::work_object},
    {"tip_radius_mm", &TracedSurface::tip_radius_m, format::kMm},
    {"contact_E_star_Pa", &TracedSurface::contact_E_star_Pa, 1.0, Need::optional},
    {"normals_from_grid", &TracedSurface::normals_from_grid, 1.0, Need::written},
    {"complete", &TracedSurface::complete, 1.0, Need::optional},
    {"resume_index", &TracedSurface::resume_index},
    {"stopped_because", &TracedSurface::stopped_because, 1.0, Need::optional},
};

json point_json(const TracePoint& p) {
  json j = {{"row", p.row}, {"column", p.column}, {"ok", p.ok}};
  if (!p.ok) {
    j["reason"] = p.reason;
    return j;
  }
  j["contact_mm"] = {p.x_m * format::kMm, p.y_m * format::kMm, p.z_m * format::kMm};
  j["apex_mm"] = {p.apex_x_m * format::kMm, p.apex_y_m * format::kMm, p.apex_z_m * format::kMm};
  j["normal"] = {p.normal[0], p.normal[1], p.normal[2]};
  format::write_fields(j, p, kTracePointFields);
  return j;
}

TracePoint point_from(const json& j, const std::string& where) {
  if (!j.is_object()) throw ConfigError(where + ": must be an object");
  const format::JsonSource src(j, where);
  TracePoint p;
  p.row = static_cast<int>(src.integer("row", {}));
  p.column = static_cast<int>(src.integer("column", {}));
  p.ok = src.boolean("ok");
  if (!p.ok) {
    p.reason = src.has("reason") ? src.text("reason") : std::string{};
    return p;
  }
  format::read_fields(src, p, kTracePointFields);
  return p;
}

}  // namespace

namespace detail {

json trace_to_json(const TracedSurface& s) {
  json j = {{"format", "palp.trace/1"}};
  format::write_fields(j, s, kSurfaceFields);
  json pts = json::array();
  for (const TracePoint& p : s.points) pts.push_back(point_json(p));
  j["points"] = std::move(pts);
  return j;
}

json point_to_json(const TracePoint& p) { return point_json(p); }
TracePoint point_from_json(const json& j, const std::string& where) { return point_from(j, where); }

void write_json_atomically(const std::filesystem::path& file, const json& j) {
  const std::filesystem::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!out) throw ConfigError(tmp.string() + ": cannot be written");
    out << j.dump(1) << "\n";
    out.flush();
    if (!out) throw ConfigError(tmp.string() + ": write failed");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) throw ConfigError(file.string() + ": cannot be replaced: " + ec.message());
}

json read_json_file(const std::filesystem::path& file) {
  const std::string text = format::read_bounded_or(
      file, format::kMaxJsonFileBytes,
      [&](const std::string& problem) -> void { throw ConfigError(file.string() + ": " + problem); });
  try {
    return json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for 1e999
    throw ConfigError(file.string() + ": not JSON (" +
                      format::escaped(e.what(), 4 * format::kQuoteChars) + ")");
  }
}

TracedSurface trace_from_json(const json& j, const std::string& f) {
  if (!has_format(j, "palp.trace/1"))
    throw ConfigError(f + ": not a trace (\"format\" is not \"palp.trace/1\")");
  TracedSurface s;
  format::read_fields(format::JsonSource(j, f), s, kSurfaceFields);
  const auto pts = j.find("points");
  if (pts == j.end() || !pts->is_array()) throw ConfigError(f + ": \"points\" must be an array");
  for (std::size_t k = 0; k < pts->size(); ++k)
    s.points.push_back(point_from((*pts)[k], f + ": points[" + std::to_string(k) + "]"));
  if (s.rows < 1 || s.columns < 1 || s.points.size() > static_cast<std::size_t>(s.rows * s.columns) ||
      s.resume_index != s.points.size())
    throw ConfigError(f + ": " + std::to_string(s.points.size()) + " points, resume_index " +
                      std::to_string(s.resume_index) + " do not fit a " + std::to_string(s.rows) +
                      " x " + std::to_string(s.columns) + " grid");
  finish_surface(s);
  return s;
}

}  // namespace detail

void save_trace(const std::filesystem::path& file, const TracedSurface& s) {
  detail::write_json_atomically(file, detail::trace_to_json(s));
}

TracedSurface load_trace(const std::filesystem::path& file) {
  const json j = detail::read_json_file(file);
  if (!detail::has_format(j, "palp.trace/1"))
    throw ConfigError(file.string() + ": not a trace file (\"format\" is not \"palp.trace/1\")");
  return detail::trace_from_json(j, file.string());
}

}  // namespace palp
