// SPDX-License-Identifier: Apache-2.0
// map_plan: touch, indent, retract at every point of a plan; map.json after every point.
#include "palp/map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "palp/force_limit.hpp"
#include "palp/result.hpp"
#include "map_align.hpp"
#include "toucher.hpp"
#include "format/field_table.hpp"
#include "map_dynamic_step.hpp"
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
    // alignment (docs/result-format.md "Maps")
    {"align", &MapPoint::aligned_by, 1.0, Need::optional},
    {"tilt_deg", &MapPoint::tilt_rad, format::kDeg, Need::optional},
    {"tool_axis", &MapPoint::tool_axis, 1.0, Need::optional},
    {"coil_offset_A", &MapPoint::coil_offset_A, 1.0, Need::optional},
};

const Field<StiffnessMap> kMapFields[] = {
    {"plan", &StiffnessMap::plan_name, 1.0, Need::optional},
    {"rows", &StiffnessMap::rows, 1.0, Need::optional},
    {"columns", &StiffnessMap::columns, 1.0, Need::optional},
    {"complete", &StiffnessMap::complete, 1.0, Need::optional},
    {"resume_index", &StiffnessMap::resume_index, 1.0, Need::optional},
    {"stopped_because", &StiffnessMap::stopped_because, 1.0, Need::optional},
    {"max_force_N", &StiffnessMap::max_force_N, 1.0, Need::optional},
};

// map.json's "adaptive" object (the planner's options, resolved; "ended" read separately)
const Field<analysis::AdaptiveGridOptions> kAdaptiveFields[] = {
    {"max_points", &analysis::AdaptiveGridOptions::max_points, 1.0, Need::required},
    {"threshold", &analysis::AdaptiveGridOptions::threshold, 1.0, Need::required},
    {"coarse_points", &analysis::AdaptiveGridOptions::coarse_points, 1.0, Need::required},
};

}  // namespace

json map_to_json(const StiffnessMap& m) {
  json pts = json::array();
  for (const MapPoint& p : m.points) {
    json q;
    format::write_fields(q, p, kMapPointFields);
    write_dynamic_point(q, p);
    pts.push_back(std::move(q));
  }
  json j = {{"format", "palp.map/1"},
            {"settings", indentation_settings_json(m.settings)},
            {"surface", detail::trace_to_json(m.surface)},
            {"points", pts}};
  format::write_fields(j, m, kMapFields);
  if (m.adaptive)
    j["adaptive"] = {{"max_points", m.adaptive->max_points},
                     {"threshold", m.adaptive->threshold},
                     {"coarse_points", m.adaptive->coarse_points},
                     {"ended", m.adaptive_ended}};
  if (m.dynamic) j["dynamic"] = identification_settings_json(*m.dynamic);
  return j;
}

namespace {

/// The options with their defaults resolved (as map.json keeps them), validated for the grid.
analysis::AdaptiveGridOptions resolved(const analysis::AdaptiveGridOptions& o, int rows,
                                       int columns) {
  o.validate(rows, columns);
  analysis::AdaptiveGridOptions r = o;
  r.max_points = o.budget(rows, columns);
  r.coarse_points = o.coarse_size(rows, columns);
  return r;
}

std::string adaptive_text(const analysis::AdaptiveGridOptions& o) {
  char threshold[32];
  std::snprintf(threshold, sizeof threshold, "%g", o.threshold);
  return "max_points " + std::to_string(o.max_points) + ", threshold " + threshold +
         ", coarse_points " + std::to_string(o.coarse_points);
}

/// The planner's next point after the map's points (absent: done, with why in `ended`).
std::optional<analysis::GridCell> next_adaptive(const StiffnessMap& m, std::string& ended) {
  std::vector<analysis::MeasuredCell> measured;
  for (const MapPoint& p : m.points) measured.push_back({p.row, p.column, p.k_fd_N_per_m});
  const analysis::AdaptiveStep s =
      analysis::next_adaptive_point(m.rows, m.columns, *m.adaptive, measured);
  if (!s.next) ended = s.phase;
  return s.next;
}

class Mapper {
 public:
  Mapper(Probe& probe, Robot& robot, const Rig& rig, const Plan& plan, const std::filesystem::path& dir,
         const MapOptions& o)
      : probe_(probe), robot_(robot), rig_(touch_rig(rig, o.settings)), plan_(plan), dir_(dir), o_(o),
        toucher_(probe, robot, rig_, o.cancelled),
        aligner_(toucher_, rig_, plan, o),
        dynamic_(o.dynamic.enabled
                     ? std::optional<IdentificationSettings>(
                           o.dynamic.settings.value_or(map_dynamic_settings(o.settings)))
                     : std::nullopt) {
    rig.validate();
    plan.validate();
    if (!rig.work_object)
      throw ConfigError("the rig has no registered work object: run `palpctl touch-off` first");
    if (!plan.work_object.empty() && plan.work_object != rig.work_object->name)
      throw ConfigError("the plan is in work object '" + plan.work_object + "' but the rig's is '" +
                        rig.work_object->name + "'");
    o.settings.validate();
    if (o.max_force_N) check_max_force(o.settings, *o.max_force_N, CoilLimits::of(probe.params()));
    if (dynamic_) detail::check_dynamic_settings(*dynamic_, o.settings);
    toucher_.set_work_object(rig.work_object->pose);
    aligner_.check();
  }

  StiffnessMap run() {
    const std::filesystem::path file = dir_ / "map.json";
    StiffnessMap m;
    std::optional<analysis::AdaptiveGridOptions> adaptive;
    if (o_.adaptive) adaptive = resolved(*o_.adaptive, plan_.grid.rows, plan_.grid.columns);
    if (o_.resume) {
      m = load_map(dir_);
      if (m.rows != plan_.grid.rows || m.columns != plan_.grid.columns)
        throw ConfigError((file).string() + ": a " + std::to_string(m.rows) + " x " + std::to_string(m.columns) +
                          " map, the plan is " + std::to_string(plan_.grid.rows) + " x " +
                          std::to_string(plan_.grid.columns));
      // a resumed map goes on as it started: the same planner options, or the regular grid
      if (adaptive && !m.adaptive)
        throw ConfigError(file.string() + ": a regular map; it resumes without adaptive options");
      if (adaptive && *adaptive != *m.adaptive)
        throw ConfigError(file.string() + ": an adaptive map with " + adaptive_text(*m.adaptive) +
                          "; it resumes with the same options (or none), not " +
                          adaptive_text(*adaptive));
    } else {
      if (std::filesystem::exists(file))
        throw ConfigError(file.string() + " exists: resume it, or map into another directory");
      m.adaptive = adaptive;
    }
    check_points_replaceable(m);
    std::filesystem::create_directories(dir_ / "points");
    m.plan_name = plan_.name;
    m.rows = plan_.grid.rows;
    m.columns = plan_.grid.columns;
    m.settings = o_.settings;
    m.max_force_N = o_.max_force_N;
    if (o_.resume && m.dynamic.has_value() != dynamic_.has_value())  // dynamic: as it began
      throw ConfigError(file.string() +
                        (m.dynamic ? ": a dynamic map: resume it with the dynamic option"
                                   : ": a quasi-static map: resume it without the dynamic option"));
    m.dynamic = dynamic_;
    m.surface.plan_name = plan_.name;
    m.surface.rows = m.rows;
    m.surface.columns = m.columns;
    m.surface.work_object = rig_.work_object->pose;
    m.surface.tip_radius_m = rig_.tip_radius_m;
    m.surface.contact_E_star_Pa = plan_.contact_E_star_Pa;
    m.complete = false;
    m.stopped_because.clear();
    m.stopped_error = nullptr;
    m.adaptive_ended.clear();
    const std::size_t total =
        m.adaptive ? static_cast<std::size_t>(m.adaptive->max_points)
                   : static_cast<std::size_t>(m.rows) * static_cast<std::size_t>(m.columns);
    try {
      toucher_.check_cancelled();
      toucher_.rise_to(rig_.safe_height_m + detail::kFullStrokeM);
      if (o_.align_to_normal) {  // the upright coil's floating position: the tilts' reference
        toucher_.turn_upright();
        toucher_.compensate_tilt(true);
      }
      // the next point: row-major, or the planner's from the points measured (as map.json has them)
      auto next = [&]() -> std::optional<analysis::GridCell> {
        if (m.adaptive) return next_adaptive(m, m.adaptive_ended);
        const std::size_t k = m.points.size();
        if (k >= total) return std::nullopt;
        return analysis::GridCell{static_cast<int>(k) / m.columns + 1,
                                  static_cast<int>(k) % m.columns + 1};
      };
      for (auto at = next(); at; at = next()) {
        toucher_.check_cancelled();
        MapPoint p = map_point(at->row, at->column);
        m.points.push_back(p);
        m.surface.points.push_back(p.surface);
        m.surface.resume_index = m.resume_index = m.points.size();
        const json doc = map_to_json(m);
        detail::write_json_atomically(file, doc);
        // go on with the numbers as map.json keeps them (N/mm): a resumed map decides the same
        format::read_fields(format::JsonSource(doc["points"].back(), file.string()),
                            m.points.back(), kMapPointFields);
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
  void check_points_replaceable(const StiffnessMap& m) const {
    for (int row = 1; row <= plan_.grid.rows; ++row)
      for (int column = 1; column <= plan_.grid.columns; ++column)
        if (std::none_of(m.points.begin(), m.points.end(),
                         [&](const MapPoint& p) { return p.row == row && p.column == column; })) {
          check_replaceable(dir_ / point_dir(row, column));
          if (dynamic_) check_replaceable(dir_ / detail::dynamic_dir_of(point_dir(row, column)));
        }
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
    // along the work object's z or the surface normal (map_align.hpp)
    const detail::MapAim aim = aligner_.aim(row, column, clearance);
    p.aligned_by = aim.aligned_by;
    p.tilt_rad = aim.tilt_rad;
    p.tool_axis = aim.tool_axis;
    Touch t;
    t.reason = aim.reason;
    if (aim.ok)
      t = toucher_.touch(aim.start, rig_.safe_height_m + rig_.max_approach_m,
                         plan_.approach_speed_m_per_s);
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
    // a tilted coil floats and ramps with the current that makes up its weight along the axis
    p.coil_offset_A = toucher_.current_offset_A();
    IndentationRun run = indent(
        probe_, detail::with_current_offset(point_settings(), p.coil_offset_A), {}, o_.cancelled);
    if (run.interrupted) throw Toucher::Cancelled{};
    if (const auto top = ramp_top_of(run)) reached_depth_m_ = top->depth_m;
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
    // dynamic: identify the contact where the ramp ended (identify() floats the coil to the
    // surface again and holds the bias; a tilted coil with the ramp's current offset)
    if (dynamic_ && !detail::identify_map_point(probe_,
                                                detail::with_current_offset(*dynamic_, p.coil_offset_A),
                                                run, dir_, p, o_.cancelled))
      throw Toucher::Cancelled{};
    // back off the surface along the tool's -z before anything moves sideways; the next touch
    // floats the coil again
    robot_.move_lin_rel(Pose{0, 0, -(rig_.safe_height_m + floating), 0, 0, 0}, rig_.travel_speed_m_per_s);
    return p;
  }

  /// The ramp for the next point: the settings', or with max_force_N its top for that force at
  /// the depth the previous point reached (0 for the first: F_o stops k_v delta short of F).
  IndentationSettings point_settings() const {
    if (!o_.max_force_N) return o_.settings;
    return settings_for_max_force(o_.settings, *o_.max_force_N, reached_depth_m_);
  }

  double reached_depth_m_ = 0;
  Probe& probe_;
  Robot& robot_;
  Rig rig_;
  const Plan& plan_;
  std::filesystem::path dir_;
  const MapOptions& o_;
  Toucher toucher_;
  detail::MapAligner aligner_;
  std::optional<IdentificationSettings> dynamic_;  ///< the dynamic map's identification
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
  if (const auto d = j.find("dynamic"); d != j.end() && !d->is_null())
    try {
      m.dynamic = identification_settings_from_json(*d);
    } catch (const ConfigError& e) {
      throw ConfigError(f + ": dynamic: " + e.what());
    }
  m.surface = detail::trace_from_json(j.value("surface", json()), f + ": surface");
  const auto pts = j.find("points");
  if (pts == j.end() || !pts->is_array()) throw ConfigError(f + ": \"points\" must be an array");
  for (std::size_t k = 0; k < pts->size(); ++k) {
    const json& q = (*pts)[k];
    if (!q.is_object()) throw ConfigError(f + ": points[" + std::to_string(k) + "] must be an object");
    MapPoint p;
    format::read_fields(format::JsonSource(q, f + ": points[" + std::to_string(k) + "]"), p, kMapPointFields);
    read_dynamic_point(q, f + ": points[" + std::to_string(k) + "]", p);
    m.points.push_back(p);
  }
  if (m.rows < 1 || m.columns < 1 || m.points.size() != m.resume_index ||
      m.surface.points.size() != m.points.size() ||
      m.points.size() > static_cast<std::size_t>(m.rows * m.columns))
    throw ConfigError(f + ": " + std::to_string(m.points.size()) + " points, resume_index " +
                      std::to_string(m.resume_index) + " do not fit a " + std::to_string(m.rows) + " x " +
                      std::to_string(m.columns) + " map");
  // any order (an adaptive map's is the planner's), each point on the grid once
  std::vector<char> seen(static_cast<std::size_t>(m.rows * m.columns), 0);
  for (std::size_t k = 0; k < m.points.size(); ++k) {
    const MapPoint& p = m.points[k];
    const std::string where = f + ": points[" + std::to_string(k) + "] (row " +
                              std::to_string(p.row) + ", column " + std::to_string(p.column) + ")";
    if (p.row < 1 || p.row > m.rows || p.column < 1 || p.column > m.columns)
      throw ConfigError(where + " is outside the " + std::to_string(m.rows) + " x " +
                        std::to_string(m.columns) + " grid");
    if (seen[static_cast<std::size_t>((p.row - 1) * m.columns + p.column - 1)]++)
      throw ConfigError(where + " is there twice");
  }
  if (const auto a = j.find("adaptive"); a != j.end() && !a->is_null()) {
    if (!a->is_object()) throw ConfigError(f + ": \"adaptive\" must be an object");
    const format::JsonSource src(*a, f + ": adaptive");
    analysis::AdaptiveGridOptions o;
    format::read_fields(src, o, kAdaptiveFields);
    m.adaptive_ended = a->value("ended", std::string());
    try {
      o.validate(m.rows, m.columns);
    } catch (const ConfigError& e) {
      throw ConfigError(f + ": adaptive: " + e.what());
    }
    m.adaptive = o;
  }
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
  a.measured.assign(a.k_N_per_m.size(), false);
  std::vector<analysis::MeasuredCell> cells;
  for (const MapPoint& p : m.points)
    if (p.row >= 1 && p.row <= m.rows && p.column >= 1 && p.column <= m.columns) {
      a.measured[static_cast<std::size_t>((p.row - 1) * m.columns + p.column - 1)] = true;
      cells.push_back({p.row, p.column, p.k_fd_N_per_m});
    }
  if (m.adaptive && std::find(a.measured.begin(), a.measured.end(), false) != a.measured.end()) {
    // an adaptive map's points not measured: the additive fit's line means, unbiased by which were
    const analysis::LineMeans lm = analysis::line_means(m.rows, m.columns, cells);
    a.column_mean_N_per_m = lm.column;
    a.row_mean_N_per_m = lm.row;
  } else {
    for (int c = 1; c <= m.columns; ++c) a.column_mean_N_per_m.push_back(mean(false, c));
    for (int r = 1; r <= m.rows; ++r) a.row_mean_N_per_m.push_back(mean(true, r));
  }
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
