// Trace files: a TracedSurface as JSON in lab units (docs/rig-and-plan.md "Trace files").
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "palp/error.hpp"
#include "palp/trace.hpp"
#include "trace_json.hpp"

namespace palp {

namespace {

using nlohmann::json;
constexpr double kDeg = 180.0 / 3.14159265358979323846;

json pose_json(const Pose& p) {
  return json::array({p.x_m * 1e3, p.y_m * 1e3, p.z_m * 1e3, p.a_rad * kDeg, p.b_rad * kDeg, p.c_rad * kDeg});
}

Pose pose_from(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 6)
    throw ConfigError(what + ": expected [x_mm, y_mm, z_mm, a_deg, b_deg, c_deg]");
  for (const json& v : j)
    if (!v.is_number()) throw ConfigError(what + ": every element must be a number");
  return Pose{j[0].get<double>() * 1e-3, j[1].get<double>() * 1e-3, j[2].get<double>() * 1e-3,
              j[3].get<double>() / kDeg,  j[4].get<double>() / kDeg,  j[5].get<double>() / kDeg};
}

json point_json(const TracePoint& p) {
  json j = {{"row", p.row}, {"column", p.column}, {"ok", p.ok}};
  if (!p.ok) {
    j["reason"] = p.reason;
    return j;
  }
  j["contact_mm"] = {p.x_m * 1e3, p.y_m * 1e3, p.z_m * 1e3};
  j["apex_mm"] = {p.apex_x_m * 1e3, p.apex_y_m * 1e3, p.apex_z_m * 1e3};
  j["normal"] = {p.normal[0], p.normal[1], p.normal[2]};
  j["tilt_deg"] = p.tilt_rad * kDeg;
  j["detection_force_N"] = p.detection_force_N;
  j["contact_stiffness_N_per_mm"] =
      p.contact_stiffness_N_per_m ? json(*p.contact_stiffness_N_per_m * 1e-3) : json(nullptr);
  j["indentation_mm"] = p.indentation_m * 1e3;
  j["overtravel_mm"] = p.overtravel_m * 1e3;
  j["guard_fired"] = p.guard_fired;
  j["tcp_at_rest_mm_deg"] = pose_json(p.tcp_at_rest);
  j["stroke_at_rest_mm"] = p.stroke_at_rest_m * 1e3;
  return j;
}

double num(const json& j, const char* key, const std::string& where) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_number()) throw ConfigError(where + ": \"" + key + "\" must be a number");
  return it->get<double>();
}

TracePoint point_from(const json& j, const std::string& where) {
  if (!j.is_object()) throw ConfigError(where + ": must be an object");
  TracePoint p;
  p.row = static_cast<int>(num(j, "row", where));
  p.column = static_cast<int>(num(j, "column", where));
  const auto ok = j.find("ok");
  if (ok == j.end() || !ok->is_boolean()) throw ConfigError(where + ": \"ok\" must be true or false");
  p.ok = ok->get<bool>();
  if (!p.ok) {
    p.reason = j.value("reason", std::string{});
    return p;
  }
  // the measured part; finish_surface derives the rest again
  p.detection_force_N = num(j, "detection_force_N", where);
  const auto kc = j.find("contact_stiffness_N_per_mm");
  if (kc != j.end() && !kc->is_null()) p.contact_stiffness_N_per_m = num(j, "contact_stiffness_N_per_mm", where) * 1e3;
  p.overtravel_m = num(j, "overtravel_mm", where) * 1e-3;
  p.guard_fired = static_cast<int>(num(j, "guard_fired", where));
  p.tcp_at_rest = pose_from(j.value("tcp_at_rest_mm_deg", json()), where + ": tcp_at_rest_mm_deg");
  p.stroke_at_rest_m = num(j, "stroke_at_rest_mm", where) * 1e-3;
  return p;
}

}  // namespace

namespace detail {

json trace_to_json(const TracedSurface& s) {
  json j = {{"format", "palp.trace/1"},
            {"plan", s.plan_name},
            {"rows", s.rows},
            {"columns", s.columns},
            {"work_object_mm_deg", pose_json(s.work_object)},
            {"tip_radius_mm", s.tip_radius_m * 1e3},
            {"contact_E_star_Pa", s.contact_E_star_Pa ? json(*s.contact_E_star_Pa) : json(nullptr)},
            {"normals_from_grid", s.normals_from_grid},
            {"complete", s.complete},
            {"resume_index", s.resume_index},
            {"stopped_because", s.stopped_because}};
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
  std::ifstream in(file);
  if (!in) throw ConfigError(file.string() + ": cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  try {
    return json::parse(ss.str());
  } catch (const json::parse_error& e) {
    throw ConfigError(file.string() + ": not JSON (" + e.what() + ")");
  }
}

TracedSurface trace_from_json(const json& j, const std::string& f) {
  if (!j.is_object() || j.value("format", std::string{}) != "palp.trace/1")
    throw ConfigError(f + ": not a trace (\"format\" is not \"palp.trace/1\")");
  TracedSurface s;
  s.plan_name = j.value("plan", std::string{});
  s.rows = static_cast<int>(num(j, "rows", f));
  s.columns = static_cast<int>(num(j, "columns", f));
  s.work_object = pose_from(j.value("work_object_mm_deg", json()), f + ": work_object_mm_deg");
  s.tip_radius_m = num(j, "tip_radius_mm", f) * 1e-3;
  const auto es = j.find("contact_E_star_Pa");
  if (es != j.end() && !es->is_null()) s.contact_E_star_Pa = num(j, "contact_E_star_Pa", f);
  s.complete = j.value("complete", false);
  s.resume_index = static_cast<std::size_t>(num(j, "resume_index", f));
  s.stopped_because = j.value("stopped_because", std::string{});
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
  if (!j.is_object() || j.value("format", std::string{}) != "palp.trace/1")
    throw ConfigError(file.string() + ": not a trace file (\"format\" is not \"palp.trace/1\")");
  return detail::trace_from_json(j, file.string());
}

}  // namespace palp
