// SPDX-License-Identifier: Apache-2.0
// map_plan: touch, indent, retract at every point of a plan; map.json after every point.
#include "palp/map.hpp"

#include <algorithm>
#include <cmath>

#include "palp/result.hpp"
#include "toucher.hpp"
#include "format/field_table.hpp"
#include "trace_json.hpp"

namespace palp {

namespace {

using detail::Toucher;
using nlohmann::json;

using format::Field;
using format::Need;

// every key optional on reading: an older or partial map.json reads with the defaults
const Field<MapPoint> kMapPointFields[] = {
    {"row", &MapPoint::row, 1.0, Need::optional},
    {"column", &MapPoint::column, 1.0, Need::optional},
    {"indented", &MapPoint::indented, 1.0, Need::optional},
    {"reason", &MapPoint::reason, 1.0, Need::optional},
    {"k_fd_N_per_mm", &MapPoint::k_fd_N_per_m, format::kNPerMm, Need::optional},
    {"k_fd_N_per_mm_reason", &MapPoint::k_fd_reason, 1.0, Need::optional},
    {"delta0_mm", &MapPoint::delta0_m, format::kMm, Need::optional},
    {"k_tangent_N_per_mm", &MapPoint::k_tangent_N_per_m, format::kNPerMm, Need::optional},
    {"result_dir", &MapPoint::result_dir, 1.0, Need::optional},
};

const Field<StiffnessMap> kMapFields[] = {
    {"plan", &StiffnessMap::plan_name, 1.0, Need::optional},
    {"rows", &StiffnessMap::rows, 1.0, Need::optional},
    {"columns", &StiffnessMap::columns, 1.0, Need::optional},
    {"complete", &StiffnessMap::complete, 1.0, Need::optional},
    {"resume_index", &StiffnessMap::resume_index, 1.0, Need::optional},
    {"stopped_because", &StiffnessMap::stopped_because, 1.0, Need::optional},
};

}  // namespace

json map_to_json(const StiffnessMap& m) {
  json pts = json::array();
  for (const MapPoint& p : m.points) {
    json q;
    format::write_fields(q, p, kMapPointFields);
    pts.push_back(std::move(q));
  }
  json j = {{"format", "palp.map/1"},
            {"settings", indentation_settings_json(m.settings)},
            {"surface", detail::trace_to_json(m.surface)},
            {"points", pts}};
  format::write_fields(j, m, kMapFields);
  return j;
}

namespace {

class Mapper {
 public:
  Mapper(Probe& probe, Robot& robot, const Rig& rig, const Plan& plan, const std::filesystem::path& dir,
         const MapOptions& o)
      : probe_(probe), robot_(robot), rig_(touch_rig(rig, o.settings)), plan_(plan), dir_(dir), o_(o),
        toucher_(probe, robot, rig_, o.cancelled) {
    rig.validate();
    plan.validate();
    if (!rig.work_object)
      throw ConfigError("the rig has no registered work object: run `palpctl touch-off` first");
    if (!plan.work_object.empty() && plan.work_object != rig.work_object->name)
      throw ConfigError("the plan is in work object '" + plan.work_object + "' but the rig's is '" +
                        rig.work_object->name + "'");
    o.settings.validate();
    toucher_.set_work_object(rig.work_object->pose);
  }

  StiffnessMap run() {
    const std::filesystem::path file = dir_ / "map.json";
    StiffnessMap m;
    if (o_.resume) {
      m = load_map(dir_);
      if (m.rows != plan_.grid.rows || m.columns != plan_.grid.columns)
        throw ConfigError((file).string() + ": a " + std::to_string(m.rows) + " x " + std::to_string(m.columns) +
                          " map, the plan is " + std::to_string(plan_.grid.rows) + " x " +
                          std::to_string(plan_.grid.columns));
    } else {
      if (std::filesystem::exists(file))
        throw ConfigError(file.string() + " exists: resume it, or map into another directory");
    }
    check_points_replaceable(m.resume_index);
    std::filesystem::create_directories(dir_ / "points");
    m.plan_name = plan_.name;
    m.rows = plan_.grid.rows;
    m.columns = plan_.grid.columns;
    m.settings = o_.settings;
    m.surface.plan_name = plan_.name;
    m.surface.rows = m.rows;
    m.surface.columns = m.columns;
    m.surface.work_object = rig_.work_object->pose;
    m.surface.tip_radius_m = rig_.tip_radius_m;
    m.surface.contact_E_star_Pa = plan_.contact_E_star_Pa;
    m.complete = false;
    m.stopped_because.clear();
    m.stopped_error = nullptr;
    const std::size_t total = static_cast<std::size_t>(m.rows) * static_cast<std::size_t>(m.columns);
    try {
      toucher_.check_cancelled();
      toucher_.rise_to(rig_.safe_height_m + detail::kFullStrokeM);
      for (std::size_t k = m.resume_index; k < total; ++k) {
        toucher_.check_cancelled();
        const int row = static_cast<int>(k) / m.columns + 1, column = static_cast<int>(k) % m.columns + 1;
        MapPoint p = map_point(row, column);
        m.points.push_back(p);
        m.surface.points.push_back(p.surface);
        m.surface.resume_index = m.resume_index = k + 1;
        detail::write_json_atomically(file, map_to_json(m));
        if (o_.progress) o_.progress(MapProgress{m.resume_index, total, &m.points.back(), "done"});
      }
      m.complete = m.surface.complete = true;
    } catch (const Toucher::Cancelled&) {
      m.stopped_because = "cancelled";
      toucher_.make_safe_and_raise();
    } catch (const std::exception& e) {
      m.stopped_because = e.what();
      m.stopped_error = std::current_exception();
      toucher_.make_safe_and_raise();
    }
    finish_surface(m.surface);
    for (std::size_t k = 0; k < m.points.size(); ++k) m.points[k].surface = m.surface.points[k];
    detail::write_json_atomically(file, map_to_json(m));
    return m;
  }

 private:
  /// Before anything moves: every point still to map whose result directory exists must be one
  /// palp wrote (a crash after writing it and before recording it in map.json leaves one, and
  /// it is replaced); anything else there is refused, naming it, and never deleted.
  void check_points_replaceable(std::size_t from) const {
    const std::size_t total = static_cast<std::size_t>(plan_.grid.rows) * static_cast<std::size_t>(plan_.grid.columns);
    for (std::size_t k = from; k < total; ++k)
      check_replaceable(dir_ / point_dir(static_cast<int>(k) / plan_.grid.columns + 1,
                                         static_cast<int>(k) % plan_.grid.columns + 1));
  }

  static std::string point_dir(int row, int column) {
    return "points/r" + std::to_string(row) + "_c" + std::to_string(column);
  }

  /// The touch floats the coil at the ramp's start current (I_c), so the ramp starts in contact.
  static Rig touch_rig(Rig r, const IndentationSettings& s) {
    r.watch_current_A = s.start_A;
    return r;
  }

  MapPoint map_point(int row, int column) {
    MapPoint p;
    p.row = row;
    p.column = column;
    // float the coil where the arm is (raised by the previous point's back-off, or at the start
    // by a whole stroke), then go above the point with the floating tip at the safe height
    toucher_.prepare();
    const double clearance = rig_.safe_height_m + toucher_.floating_stroke_m();
    toucher_.rise_to(clearance);
    const Pose start = toucher_.tcp_at(plan_.x_m(column - 1), plan_.y_m(row - 1), -clearance);
    Touch t = toucher_.touch(start, rig_.safe_height_m + rig_.max_approach_m, plan_.approach_speed_m_per_s);
    p.surface = t.at_rest;
    p.surface.row = row;
    p.surface.column = column;
    p.surface.ok = t.ok;
    p.surface.reason = t.reason;
    if (!t.ok) {
      p.reason = "no surface: " + t.reason;
      return p;
    }
    // the ramp: indent() zeroes the pressures with the coil at 0 A and floats it again
    const double floating = toucher_.floating_stroke_m();
    toucher_.release_coil();
    toucher_.wait_device(1.2);  // the coil back on its rear stop and at rest (ring-down)
    IndentationRun run = indent(probe_, o_.settings, {}, o_.cancelled);
    if (run.interrupted) throw Toucher::Cancelled{};
    p.result_dir = point_dir(row, column);
    write_result(dir_ / p.result_dir, run, Overwrite::yes);
    p.indented = true;
    if (run.analysis) {
      const analysis::IndentationResult& a = *run.analysis;
      p.k_fd_N_per_m = a.k_fd_N_per_m.value;
      p.k_fd_reason = a.k_fd_N_per_m.reason;
      p.delta0_m = a.delta0_m.value;
      p.k_tangent_N_per_m = a.k_tangent_at_delta0_N_per_m.value;
    } else {
      p.k_fd_reason = run.analysis_reason;
    }
    // back off the surface along the tool's -z before anything moves sideways; the next touch
    // floats the coil again
    robot_.move_lin_rel(Pose{0, 0, -(rig_.safe_height_m + floating), 0, 0, 0}, rig_.travel_speed_m_per_s);
    return p;
  }

  Probe& probe_;
  Robot& robot_;
  Rig rig_;
  const Plan& plan_;
  std::filesystem::path dir_;
  const MapOptions& o_;
  Toucher toucher_;
};

}  // namespace

StiffnessMap map_plan(Probe& probe, Robot& robot, const Rig& rig, const Plan& plan,
                      const std::filesystem::path& dir, const MapOptions& options) {
  return Mapper(probe, robot, rig, plan, dir, options).run();
}

void save_map(const std::filesystem::path& dir, const StiffnessMap& m) {
  std::filesystem::create_directories(dir);
  detail::write_json_atomically(dir / "map.json", map_to_json(m));
}

StiffnessMap load_map(const std::filesystem::path& dir) {
  const std::filesystem::path file = dir / "map.json";
  return map_from_json(detail::read_json_file(file), file.string());
}

StiffnessMap map_from_json(const json& j, const std::string& f) {
  if (!detail::has_format(j, "palp.map/1"))
    throw ConfigError(f + ": not a map (\"format\" is not \"palp.map/1\")");
  StiffnessMap m;
  format::read_fields(format::JsonSource(j, f), m, kMapFields);
  if (const auto s = j.find("settings"); s != j.end() && !s->is_null())  // maps before it: defaults
    m.settings = indentation_settings_from_json(*s, f + ": settings.");
  m.surface = detail::trace_from_json(j.value("surface", json()), f + ": surface");
  const auto pts = j.find("points");
  if (pts == j.end() || !pts->is_array()) throw ConfigError(f + ": \"points\" must be an array");
  for (std::size_t k = 0; k < pts->size(); ++k) {
    const json& q = (*pts)[k];
    if (!q.is_object()) throw ConfigError(f + ": points[" + std::to_string(k) + "] must be an object");
    MapPoint p;
    format::read_fields(format::JsonSource(q, f + ": points[" + std::to_string(k) + "]"), p, kMapPointFields);
    m.points.push_back(p);
  }
  if (m.rows < 1 || m.columns < 1 || m.points.size() != m.resume_index ||
      m.surface.points.size() != m.points.size() ||
      m.points.size() > static_cast<std::size_t>(m.rows * m.columns))
    throw ConfigError(f + ": " + std::to_string(m.points.size()) + " points, resume_index " +
                      std::to_string(m.resume_index) + " do not fit a " + std::to_string(m.rows) + " x " +
                      std::to_string(m.columns) + " map");
  for (std::size_t k = 0; k < m.points.size(); ++k) m.points[k].surface = m.surface.points[k];
  return m;
}

MapAnalysis analyze_map(const StiffnessMap& m, double contrast) {
  MapAnalysis a;
  a.rows = m.rows;
  a.columns = m.columns;
  a.contrast = contrast;
  a.k_N_per_m.assign(static_cast<std::size_t>(m.rows * m.columns), std::nullopt);
  for (const MapPoint& p : m.points)
    if (p.row >= 1 && p.row <= m.rows && p.column >= 1 && p.column <= m.columns)
      a.k_N_per_m[static_cast<std::size_t>((p.row - 1) * m.columns + p.column - 1)] = p.k_fd_N_per_m;
  auto mean = [&](bool by_row, int line) {
    double s = 0;
    int n = 0;
    const int count = by_row ? m.columns : m.rows;
    for (int q = 1; q <= count; ++q) {
      const int r = by_row ? line : q, c = by_row ? q : line;
      const auto& k = a.k_N_per_m[static_cast<std::size_t>((r - 1) * m.columns + c - 1)];
      if (k) s += *k, ++n;
    }
    return n > 0 ? s / n : std::nan("");
  };
  for (int c = 1; c <= m.columns; ++c) a.column_mean_N_per_m.push_back(mean(false, c));
  for (int r = 1; r <= m.rows; ++r) a.row_mean_N_per_m.push_back(mean(true, r));
  std::vector<double> all;
  for (const auto& k : a.k_N_per_m)
    if (k) all.push_back(*k);
  if (!all.empty()) {
    std::nth_element(all.begin(), all.begin() + static_cast<long>(all.size() / 2), all.end());
    a.median_N_per_m = all[all.size() / 2];
  }
  // a line stands out against the median of all lines' means (a line next to a soft one is not
  // "stiff" because of it)
  auto flag = [&](const std::vector<double>& v, std::vector<int>& soft, std::vector<int>& stiff) {
    std::vector<double> finite;
    for (double x : v)
      if (std::isfinite(x)) finite.push_back(x);
    if (finite.empty()) return;
    std::sort(finite.begin(), finite.end());
    const std::size_t h = finite.size() / 2;
    const double ref = finite.size() % 2 == 1 ? finite[h] : 0.5 * (finite[h - 1] + finite[h]);
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!std::isfinite(v[i])) continue;
      if (v[i] <= (1 - contrast) * ref) soft.push_back(static_cast<int>(i) + 1);
      if (v[i] >= (1 + contrast) * ref) stiff.push_back(static_cast<int>(i) + 1);
    }
  };
  flag(a.column_mean_N_per_m, a.soft_columns, a.stiff_columns);
  flag(a.row_mean_N_per_m, a.soft_rows, a.stiff_rows);
  return a;
}

}  // namespace palp
