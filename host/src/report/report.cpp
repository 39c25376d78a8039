// SPDX-License-Identifier: Apache-2.0
// make_report: what the input is (a map, a result directory by its experiment, a trace) chooses
// the section builders (sections.hpp); the header comes from result.json, its sidecar and
// map.json.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>

#include "palp/error.hpp"
#include "palp/map.hpp"
#include "palp/report.hpp"
#include "palp/result.hpp"
#include "palp/trace.hpp"
#include "report/report_internal.hpp"
#include "report/sections.hpp"

namespace palp::report {

namespace fs = std::filesystem;
using nlohmann::json;

namespace detail {

std::string num(double v, int digits) {
  if (!std::isfinite(v)) return "–";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string fixed(double v, int decimals, bool sign) {
  if (!std::isfinite(v)) return "–";
  char buf[48];
  std::snprintf(buf, sizeof buf, sign ? "%+.*f" : "%.*f", decimals, v);
  return buf;
}

namespace {

std::string text_of(const json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer()) return v.dump();  // a count or a hash: every digit
  if (v.is_number()) return num(v.get<double>(), 6);
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (v.is_null()) return "–";
  return v.dump();
}

/// "key value, key value" of an object's present scalar members (arrays summarised by length).
std::string pairs_text(const json& j, std::initializer_list<const char*> keys) {
  std::string out;
  for (const char* k : keys) {
    const auto it = j.find(k);
    if (it == j.end() || it->is_null()) continue;
    if (!out.empty()) out += ", ";
    out += std::string(k) + " " + (it->is_array() ? std::to_string(it->size()) + " entries" : text_of(*it));
  }
  return out.empty() ? "–" : out;
}

/// Every scalar member of an object as "key value, ...", nested objects' members as
/// "outer.key value" (arrays summarised by length): settings that have no summary of their own.
std::string all_pairs_text(const json& j, const std::string& prefix = "") {
  std::string out;
  for (const auto& [k, v] : j.items()) {
    std::string part;
    if (v.is_object()) part = all_pairs_text(v, prefix + k + ".");
    else if (v.is_array()) part = prefix + k + " " + (v.empty() ? "none" : std::to_string(v.size()) + " entries");
    else part = prefix + k + " " + text_of(v);
    if (part.empty()) continue;
    if (!out.empty()) out += ", ";
    out += part;
  }
  return out;
}

double number_or(const json& j, const char* key, double fallback) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : fallback;
}

}  // namespace

std::string indentation_settings_text(const json& p) {
  if (!p.is_object()) return "–";
  std::string s = "ramp " + num(number_or(p, "start_A", NAN)) + " → " + num(number_or(p, "stop_A", NAN)) +
                  " A by " + num(number_or(p, "step_A", NAN)) + " A every " +
                  num(number_or(p, "dwell_s", NAN) * 1e3) + " ms, " + num(number_or(p, "reps", NAN)) +
                  (number_or(p, "reps", NAN) == 1 ? " repetition" : " repetitions") + ", limit " + num(number_or(p, "displacement_limit_mm", NAN)) + " mm, stream " +
                  num(number_or(p, "rate_Hz", NAN)) + " Hz";
  if (const auto a = p.find("analysis"); a != p.end() && a->is_object())
    s += "; analysis: K_f " + num(number_or(*a, "kf_N_per_A", NAN)) + " N/A, I_c " +
         num(number_or(*a, "ic_A", NAN)) + " A, k_v " + num(number_or(*a, "kv_N_per_mm", NAN)) + " N/mm, R " +
         num(number_or(*a, "tip_radius_mm", NAN)) + " mm, ν " + num(number_or(*a, "poisson", NAN)) + ", window " +
         num(number_or(*a, "window_lo_mm", NAN)) + "–" + num(number_or(*a, "window_hi_mm", NAN)) + " mm";
  return s;
}

HeaderLines result_header(const LoadedResult& r) {
  HeaderLines h;
  const json& d = r.summary.contains("device") ? r.summary["device"] : json(nullptr);
  if (d.is_object()) {
    h.emplace_back("Device", pairs_text(d, {"serial", "board", "uri"}));
    h.emplace_back("Firmware", pairs_text(d, {"firmware_version", "git_hash"}));
    h.emplace_back("Protocol", pairs_text(d, {"protocol", "schema_hash", "control_rate_Hz", "max_current_A"}));
  } else {
    h.emplace_back("Device", "not recorded");
  }
  if (!r.recordings.empty() && r.recordings.front().second.sidecar) {
    const Sidecar& side = *r.recordings.front().second.sidecar;
    h.emplace_back("Calibration", side.calibration.is_object()
                                      ? pairs_text(side.calibration, {"layout_version", "spring_k_N_per_mm",
                                                                      "current_offset_A", "current_gain",
                                                                      "kf_table", "stroke_origin_mm"})
                                      : "not recorded");
  } else {
    h.emplace_back("Calibration", "not recorded");
  }
  h.emplace_back("Experiment", r.experiment + ", " + text_of(r.summary.value("created_utc", json(nullptr))) +
                                   ", SDK " + text_of(r.summary.value("sdk_version", json(nullptr))));
  if (r.experiment == "indentation")
    h.emplace_back("Settings", indentation_settings_text(r.summary.value("parameters", json(nullptr))));
  else if (const auto p = r.summary.find("parameters"); p != r.summary.end() && p->is_object())
    h.emplace_back("Settings", all_pairs_text(*p));
  h.emplace_back("Directory", r.dir.string());
  return h;
}

}  // namespace detail

namespace {

/// A part of a report that is not its subject (the surface under a map, the pressures of an
/// indentation): when its builder cannot draw it, the section says why instead of failing the
/// whole report.
Section secondary(const char* id, const char* title, const std::function<Section()>& build) {
  try {
    return build();
  } catch (const Error& e) {
    Section s;
    s.id = id;
    s.title = title;
    s.text = std::string("Not drawn: ") + e.what();
    return s;
  }
}

Report result_report(const fs::path& dir) {
  const LoadedResult r = load_result(dir);
  Report rep;
  rep.header = detail::result_header(r);
  const std::string name = fs::absolute(dir).lexically_normal().filename().string();
  if (r.experiment == "indentation") {
    rep.title = "Indentation: " + name;
    rep.sections.push_back(indentation_section(r));
    rep.sections.push_back(secondary("pressure", "Pressure channels", [&] { return pressure_section(r); }));
  } else if (r.experiment == "identification") {
    rep.title = "Identification: " + name;
    rep.sections.push_back(identification_section(r));
  } else {
    throw ConfigError(dir.string() + ": result.json's experiment \"" + r.experiment +
                      "\" has no report (reports draw indentation and identification results, maps and traces)");
  }
  return rep;
}

detail::HeaderLines trace_header(const TracedSurface& s) {
  return {{"Plan", s.plan_name.empty() ? "–" : s.plan_name},
          {"Grid", std::to_string(s.rows) + " rows × " + std::to_string(s.columns) + " columns, " +
                       std::to_string(s.points.size()) + " points traced"},
          {"State", s.complete ? "complete" : "stopped: " + s.stopped_because},
          {"Tip radius", detail::num(s.tip_radius_m * 1e3) + " mm"},
          {"Normals", s.normals_from_grid ? "from the grid's neighbours" : "the approach axis (partial grid)"}};
}

Report map_report(const fs::path& dir) {
  const StiffnessMap m = load_map(dir);
  const MapAnalysis a = analyze_map(m);
  Report rep;
  rep.title = "Stiffness map: " + (m.plan_name.empty() ? fs::absolute(dir).lexically_normal().filename().string()
                                                       : m.plan_name);
  rep.header.emplace_back("Plan", m.plan_name.empty() ? "–" : m.plan_name);
  std::size_t indented = 0;
  for (const MapPoint& p : m.points) indented += p.indented ? 1 : 0;
  // an adaptive map measures only the points its planner chose: count them against the grid
  const std::size_t grid_points = static_cast<std::size_t>(m.rows) * static_cast<std::size_t>(m.columns);
  std::string grid = std::to_string(m.rows) + " rows × " + std::to_string(m.columns) + " columns, " +
                     std::to_string(indented) + " of " +
                     std::to_string(m.adaptive ? grid_points : m.points.size()) + " points indented";
  if (m.adaptive)
    grid += " (adaptive: " + std::to_string(m.points.size()) + " measured, budget " +
            std::to_string(m.adaptive->budget(m.rows, m.columns)) +
            (m.adaptive_ended.empty() ? std::string(")") : "; ended: " + m.adaptive_ended + ")");
  rep.header.emplace_back("Grid", grid);
  rep.header.emplace_back("State", m.complete ? "complete" : "stopped: " + m.stopped_because);
  rep.header.emplace_back("Settings", detail::indentation_settings_text(indentation_settings_json(m.settings)));
  // the instrument: from the first point's result (every point of a map is measured with it)
  for (const MapPoint& p : m.points) {
    if (p.result_dir.empty()) continue;
    try {
      for (auto& [label, value] : detail::result_header(load_result(dir / p.result_dir)))
        if (label == "Device" || label == "Firmware" || label == "Protocol" || label == "Calibration")
          rep.header.emplace_back(label, value + " (from " + p.result_dir + ")");
    } catch (const Error& e) {
      rep.header.emplace_back("Device", std::string("unknown: ") + e.what());
    }
    break;
  }
  rep.header.emplace_back("Directory", fs::absolute(dir).lexically_normal().string());
  rep.sections.push_back(map_section(m, a, dir));
  if (map_dynamic_grids(m).points_identified > 0)  // dynamic: its grids
    rep.sections.push_back(
        secondary("map-dynamic", "Viscoelastic map", [&] { return map_dynamic_section(m); }));
  if (!m.surface.points.empty())
    rep.sections.push_back(secondary("surface", "The surface", [&] { return trace_section(m.surface); }));
  return rep;
}

Report trace_report(const fs::path& file) {
  const TracedSurface s = load_trace(file);
  Report rep;
  rep.title = "Traced surface: " + (s.plan_name.empty() ? file.filename().string() : s.plan_name);
  rep.header = trace_header(s);
  rep.header.emplace_back("File", fs::absolute(file).lexically_normal().string());
  rep.sections.push_back(trace_section(s));
  return rep;
}

}  // namespace

Report make_report(const fs::path& input) {
  const std::string kinds =
      "give a map directory (map.json), a result directory (result.json) or a trace (trace.json)";
  std::error_code ec;
  const fs::file_status st = fs::status(input, ec);
  if (!fs::exists(st)) throw ConfigError(input.string() + ": no such file or directory; " + kinds);
  Report rep;
  if (fs::is_directory(st)) {
    if (fs::exists(input / "map.json", ec))
      rep = map_report(input);
    else if (fs::exists(input / kResultFile, ec))
      rep = result_report(input);
    else if (fs::exists(input / "trace.json", ec))
      rep = trace_report(input / "trace.json");
    else
      throw ConfigError(input.string() + ": neither a map (no map.json), a result (no " + std::string(kResultFile) +
                        ") nor a trace (no trace.json); " + kinds);
  } else {
    const std::string name = input.filename().string();
    if (name == "map.json")
      rep = map_report(input.parent_path().empty() ? fs::path(".") : input.parent_path());
    else if (name == kResultFile)
      rep = result_report(input.parent_path().empty() ? fs::path(".") : input.parent_path());
    else {
      try {
        rep = trace_report(input);  // any other file: a trace under another name, or nothing of palp's
      } catch (const ConfigError& e) {
        throw ConfigError(std::string(e.what()) + "; " + kinds);
      }
    }
  }
  rep.input = input.string();
  return rep;
}

}  // namespace palp::report
