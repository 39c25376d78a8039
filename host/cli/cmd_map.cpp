// SPDX-License-Identifier: Apache-2.0
// palpctl map: the stiffness map of a plan (touch, indent, retract at every point), resumable;
// palpctl analyze map: a saved map's stiffness grid and the soft and stiff lines in it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <iostream>
#include <numbers>
#include <optional>

#include "common.hpp"
#include "export_hdf5.hpp"
#include "map_dynamic_cli.hpp"
#include "palp/error.hpp"
#ifdef PALP_HAVE_HDF5
#include "palp/hdf5.hpp"
#endif
#include "palp/map.hpp"
#include "palp/result.hpp"
#include "palp/robot.hpp"
#include "palp/trace.hpp"

namespace palpctl {

namespace {

struct MapCli {
  std::string rig, plan, out_dir = "map";
  bool resume = false;
  std::string preset = "2d";
  std::optional<int> repetitions;  // the preset's when not given
  // adaptive (analysis/adaptive_grid.hpp)
  bool adaptive = false;
  int max_points = 0;
  double threshold = 0.1;
  std::optional<double> max_force_N;  // depth sensitivity: the ramp's top object force
  MapDynamicCli dynamic;           // --dynamic and its settings
  // alignment: --align, --trace, --local-trace-mm, --max-tilt-deg
  std::string align = "none", trace;
  double local_trace_mm = 2.0, max_tilt_deg = 30.0;
};

json analysis_json(const palp::MapAnalysis& a) {
  json k = json::array();
  for (int r = 0; r < a.rows; ++r) {
    json row = json::array();
    for (int c = 0; c < a.columns; ++c) {
      const auto& v = a.k_N_per_m[static_cast<std::size_t>(r * a.columns + c)];
      row.push_back(v ? json(*v * 1e-3) : json(nullptr));
    }
    k.push_back(row);
  }
  auto means = [](const std::vector<double>& v) {
    json j = json::array();
    for (double x : v) j.push_back(std::isfinite(x) ? json(x * 1e-3) : json(nullptr));
    return j;
  };
  return {{"k_fd_N_per_mm", k},
          {"column_mean_k_fd_N_per_mm", means(a.column_mean_N_per_m)},
          {"row_mean_k_fd_N_per_mm", means(a.row_mean_N_per_m)},
          {"median_k_fd_N_per_mm", a.median_N_per_m * 1e-3},
          {"contrast", a.contrast},
          {"soft_columns", a.soft_columns},
          {"stiff_columns", a.stiff_columns},
          {"soft_rows", a.soft_rows},
          {"stiff_rows", a.stiff_rows}};
}

void print_map(const palp::StiffnessMap& m, const palp::MapAnalysis& a) {
  std::printf("stiffness k_fd (N/mm, 0.25-0.75 mm), %s, %d x %d:\n      ", m.plan_name.c_str(), a.rows, a.columns);
  for (int c = 1; c <= a.columns; ++c) std::printf(" col %-3d", c);
  std::printf("\n");
  for (int r = 1; r <= a.rows; ++r) {
    std::printf("row %-2d", r);
    for (int c = 1; c <= a.columns; ++c) {
      const auto& v = a.k_N_per_m[static_cast<std::size_t>((r - 1) * a.columns + c - 1)];
      if (v)
        std::printf(" %7.4f", *v * 1e-3);
      else
        std::printf(" %7s", "-");
    }
    std::printf("\n");
  }
  auto list = [](const std::vector<int>& v) {
    std::string s;
    for (int x : v) s += (s.empty() ? "" : ", ") + std::to_string(x);
    return s.empty() ? std::string("none") : s;
  };
  std::printf("soft columns (>= %.0f %% below the median column): %s\n", 100 * a.contrast, list(a.soft_columns).c_str());
  std::printf("soft rows: %s; stiff columns: %s; stiff rows: %s\n", list(a.soft_rows).c_str(),
              list(a.stiff_columns).c_str(), list(a.stiff_rows).c_str());
}

/// An adaptive map's economy: points measured of the grid's, and the device time they took
/// against the whole grid's at the same mean time per point (the result directories' recordings).
json adaptive_json(const palp::StiffnessMap& m) {
  const int grid = m.rows * m.columns, used = static_cast<int>(m.points.size());
  return {{"points_measured", used},
          {"grid_points", grid},
          {"max_points", m.adaptive->max_points},
          {"threshold", m.adaptive->threshold},
          {"coarse_points", m.adaptive->coarse_points},
          {"ended", m.adaptive_ended},
          {"points_saved_percent", 100.0 * (grid - used) / grid}};
}

void print_adaptive(const palp::StiffnessMap& m) {
  const json j = adaptive_json(m);
  std::printf(
      "adaptive: %d of %d points measured (%.0f %% saved; coarse design %d, threshold %.0f %%, "
      "budget %d, ended: %s); '-' marks points not measured or without a value\n",
      j["points_measured"].get<int>(), j["grid_points"].get<int>(),
      j["points_saved_percent"].get<double>(), m.adaptive->coarse_points,
      100 * m.adaptive->threshold, m.adaptive->max_points,
      m.adaptive_ended.empty() ? "not yet" : m.adaptive_ended.c_str());
}

// the tool's tilt used at each point (deg; null where not touched), row-major like the analysis
json tilt_json(const palp::StiffnessMap& m) {
  json rows = json::array();
  for (int r = 0; r < m.rows; ++r) {
    json row = json::array();
    for (int c = 0; c < m.columns; ++c) row.push_back(nullptr);
    rows.push_back(row);
  }
  for (const palp::MapPoint& p : m.points)
    if (p.surface.ok && p.row >= 1 && p.row <= m.rows && p.column >= 1 && p.column <= m.columns)
      rows[static_cast<std::size_t>(p.row - 1)][static_cast<std::size_t>(p.column - 1)] =
          p.tilt_rad * 180 / std::numbers::pi;
  return rows;
}

void print_tilt(const palp::StiffnessMap& m) {
  double lo = INFINITY, hi = -INFINITY;
  std::string by = "none";
  for (const palp::MapPoint& p : m.points) {
    if (!p.surface.ok) continue;
    lo = std::min(lo, p.tilt_rad), hi = std::max(hi, p.tilt_rad);
    by = p.aligned_by;
  }
  if (by == "none" || !(lo <= hi)) return;
  std::printf("tool along the surface normal (%s): tilt %.1f to %.1f deg\n", by.c_str(),
              lo * 180 / std::numbers::pi, hi * 180 / std::numbers::pi);
}

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.15g", v);
  return b;
}

/// The command that resumes this map: its own options again (a resumed map refuses other
/// adaptive, dynamic or alignment options, so the hint must carry them), then --resume.
std::string resume_command(const MapCli& o) {
  std::string s = "palpctl map --rig " + o.rig + " --plan " + o.plan + " --out-dir " + o.out_dir;
  if (o.preset != "2d") s += " --preset " + o.preset;
  if (o.repetitions) s += " --reps " + std::to_string(*o.repetitions);
  if (o.adaptive) {
    s += " --adaptive";
    if (o.max_points != 0) s += " --max-points " + std::to_string(o.max_points);
    if (o.threshold != 0.1) s += " --threshold " + number(o.threshold);
  }
  if (o.max_force_N) s += " --max-force-N " + number(*o.max_force_N);
  if (o.dynamic.enabled) {
    s += " --dynamic";
    if (o.dynamic.amplitude_A) s += " --dynamic-amplitude-A " + number(*o.dynamic.amplitude_A);
    if (o.dynamic.measured_periods)
      s += " --dynamic-measured-periods " + std::to_string(*o.dynamic.measured_periods);
  }
  if (o.align != "none") {
    s += " --align " + o.align;
    if (!o.trace.empty()) s += " --trace " + o.trace;
    if (o.local_trace_mm != 2.0) s += " --local-trace-mm " + number(o.local_trace_mm);
    if (o.max_tilt_deg != 30.0) s += " --max-tilt-deg " + number(o.max_tilt_deg);
  }
  return s + " --resume";
}

int map(const Context& ctx, const MapCli& o) {
  const palp::Rig rig = palp::load_rig(o.rig);
  const palp::Plan plan = palp::load_plan(o.plan);
  palp::MapOptions options;
  options.settings = palp::IndentationSettings::preset(o.preset == "1d" ? palp::IndentationPreset::one_d
                                                                        : palp::IndentationPreset::two_d);
  if (o.repetitions) options.settings.repetitions = *o.repetitions;
  options.resume = o.resume;
  if (o.adaptive) {
    options.adaptive = palp::analysis::AdaptiveGridOptions{o.max_points, o.threshold, 0};
    options.adaptive->validate(plan.grid.rows, plan.grid.columns);  // before connecting: exit 2
  }
  options.max_force_N = o.max_force_N;
  options.dynamic = map_dynamic_options(o.dynamic, options.settings);
  options.align_to_normal = o.align == "normal";
  if (!o.trace.empty()) options.align_trace = palp::load_trace(o.trace);
  options.local_trace_offset_m = o.local_trace_mm * 1e-3;
  options.max_tilt_rad = o.max_tilt_deg * std::numbers::pi / 180.0;
  palp::Probe probe = ctx.connect(rig.probe_uri);
  if (o.resume) recover_for_resume(probe);
  auto robot = palp::connect_robot(rig.robot_uri);
  catch_interrupts();
  options.cancelled = [] { return interrupted(); };
  const int planned = options.adaptive ? options.adaptive->budget(plan.grid.rows, plan.grid.columns)
                                       : plan.point_count();
  Progress progress("map", static_cast<std::uint64_t>(planned), !ctx.json, "points");
  options.progress = [&](const palp::MapProgress& p) { progress.update(p.done); };
  const palp::StiffnessMap m = palp::map_plan(probe, *robot, rig, plan, o.out_dir, options);
  progress.finish(m.resume_index);
  const palp::MapAnalysis a = palp::analyze_map(m);
  json j = {{"plan", m.plan_name},        {"rows", m.rows},
            {"columns", m.columns},       {"complete", m.complete},
            {"points_done", m.resume_index}, {"map_dir", o.out_dir}};
  if (!m.complete) j["stopped_because"] = m.stopped_because;
  if (m.adaptive) j["adaptive"] = adaptive_json(m);
  j["analysis"] = analysis_json(a);
  if (json d = map_dynamic_json(m); !d.is_null()) j["analysis"]["dynamic"] = std::move(d);
  j["tilt_deg"] = tilt_json(m);
  if (ctx.json)
    print_json(j);
  else {
    print_map(m, a);
    if (m.adaptive) print_adaptive(m);
    print_map_dynamic(m);
    print_tilt(m);
    std::printf("results in %s (map.json, points/r<row>_c<column>/)\n", o.out_dir.c_str());
  }
  if (!m.complete) {
    std::cerr << "palpctl: map stopped (" << m.stopped_because << ") after " << m.resume_index
              << " points; the arm is at the safe height and the coil current is zero.\n"
              << "resume with: " << resume_command(o) << "\n";
    if (interrupted()) return kInterrupted;
    // the error that stopped it decides the exit code, as it would had it not been caught
    if (m.stopped_error) std::rethrow_exception(m.stopped_error);
    return kRuntime;
  }
  return kOk;
}

}  // namespace

int analyze_map_command(const Context& ctx, const std::string& dir, const palp::analysis::IndentationParams& params,
                        bool kf_table, double contrast) {
  // a map directory, or the same map exported as one HDF5 file (palp/hdf5.hpp)
  std::function<palp::LoadedResult(const std::string&)> result_of =
      [&dir](const std::string& result_dir) {
        return palp::load_result(std::filesystem::path(dir) / result_dir);
      };
  palp::StiffnessMap m;
#ifdef PALP_HAVE_HDF5
  auto file = std::make_shared<palp::LoadedMap>();
  if (palp::is_hdf5_file(dir)) {
    *file = palp::read_map_hdf5(dir);
    m = file->map;
    result_of = [file, &dir](const std::string& result_dir) {
      for (const auto& [name, r] : file->results)
        if (name == result_dir) return r;
      std::string why = "not in the file";
      for (const auto& [name, lost] : file->damaged)
        if (name == result_dir) why = "lost when the map was exported: " + lost;
      throw palp::RecordingError(dir, 0, "point " + result_dir + ": " + why);
    };
  } else {
    m = palp::load_map(dir);
  }
#else
  if (std::filesystem::path(dir).extension() == ".h5" && !hdf5_available())
    throw palp::ConfigError(dir + ": this palpctl was built without HDF5 and reads no .h5 (install libhdf5-dev, "
                                  "scripts/install-deps, and build again)");
  m = palp::load_map(dir);
#endif
  Progress progress("analyze map", m.points.size(), !ctx.json, "points");
  std::size_t done = 0;
  for (palp::MapPoint& p : m.points) {
    progress.update(done++);
    if (!p.indented || p.result_dir.empty()) continue;
    palp::IndentationRun run = palp::indentation_run_of(result_of(p.result_dir));
    run.settings.analysis = params;
    if (kf_table) {
      if (!run.recording.sidecar)
        throw palp::ConfigError(p.result_dir + ": --kf-table needs the recording's sidecar (none found)");
      palp::use_kf_table_of(*run.recording.sidecar, run.settings.analysis);
    }
    palp::analyze_run(run);
    p.k_fd_N_per_m.reset();
    p.delta0_m.reset();
    p.k_tangent_N_per_m.reset();
    if (run.analysis) {
      p.k_fd_N_per_m = run.analysis->k_fd_N_per_m.value;
      p.k_fd_reason = run.analysis->k_fd_N_per_m.reason;
      p.delta0_m = run.analysis->delta0_m.value;
      p.k_tangent_N_per_m = run.analysis->k_tangent_at_delta0_N_per_m.value;
    } else {
      p.k_fd_reason = run.analysis_reason;
    }
    // dynamic: the identification again from its recording, with the re-analysed indentation
    if (!p.dynamic_dir.empty())
      p.dynamic = palp::reanalyse_dynamic_point(result_of(p.dynamic_dir),
                                                run.analysis ? &*run.analysis : nullptr,
                                                run.settings.analysis);
  }
  progress.finish(done);
  const palp::MapAnalysis a = palp::analyze_map(m, contrast);
  json j = {{"plan", m.plan_name}, {"rows", m.rows}, {"columns", m.columns}, {"complete", m.complete}};
  j["params"] = palp::indentation_params_json(params);
  if (m.adaptive) j["adaptive"] = adaptive_json(m);
  j["analysis"] = analysis_json(a);
  if (json d = map_dynamic_json(m); !d.is_null()) j["analysis"]["dynamic"] = std::move(d);
  if (ctx.json)
    print_json(j);
  else {
    print_map(m, a);
    if (m.adaptive) print_adaptive(m);
    print_map_dynamic(m);
  }
  return kOk;
}

void add_map_command(CLI::App& app, Context& ctx) {
  auto o = std::make_shared<MapCli>();
  auto* cmd = app.add_subcommand(
      "map",
      "Map a plan's grid: at every point touch the surface (as trace), run the quasi-static "
      "indentation (2D protocol: 0.5 -> 3 A by 0.01 A every 25 ms, 3 repetitions), retract. "
      "Writes OUT_DIR/map.json after every point and OUT_DIR/points/r<row>_c<column>/ result "
      "directories; Ctrl-C stops safely (continue with --resume). Prints the k_fd stiffness map.");
  cmd->add_option("--rig", o->rig, "rig.json")->required()->check(CLI::ExistingFile);
  cmd->add_option("--plan", o->plan, "plan.json")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out-dir", o->out_dir, "Directory of the map")->capture_default_str();
  cmd->add_flag("--resume", o->resume, "Continue the map in OUT_DIR from its first unfinished point");
  cmd->add_option("--preset", o->preset, "Indentation protocol: 2d (25 ms, 3 reps) or 1d (100 ms, 5 reps)")
      ->check(CLI::IsMember({"1d", "2d"}))
      ->capture_default_str();
  cmd->add_option("--reps", o->repetitions, "Load/unload cycles at each point (default: the preset's, 3 or 5)")
      ->check(CLI::Range(1, 1000));
  cmd->add_flag(
      "--adaptive", o->adaptive,
      "Measure only some points: a space-filling coarse design (every row and column), then "
      "refinement where neighbouring k_fd differ by more than --threshold, up to "
      "--max-points (map.json lists the points measured, in order)");
  cmd->add_option("--max-points", o->max_points,
                  "--adaptive: the point budget (0: half the grid, at least the coarse design)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  cmd->add_option("--threshold", o->threshold,
                  "--adaptive: refine where neighbours differ by more than this fraction "
                  "(1 - k_min / k_max; 0.1: 10 %, as analyze map's --contrast)")
      ->check(CLI::Range(0.001, 0.999))
      ->capture_default_str();
  cmd->add_option("--max-force-N", o->max_force_N,
                  "Stop each ramp at this object force, N (its top current from K_f, I_c, k_v and "
                  "the depth the previous point reached); refused beyond the coil's current clamp "
                  "or I2t margin (docs/depth-sensitivity.md)");
  add_map_dynamic_options(cmd, o->dynamic);
  cmd->add_option("--align", o->align,
                  "Tool axis at each point: none (the work object's z) or normal (the surface "
                  "normal: from --trace, else a local trace of four touches around the point)")
      ->check(CLI::IsMember({"none", "normal"}))
      ->capture_default_str();
  cmd->add_option("--trace", o->trace,
                  "With --align normal: trace.json of `palpctl trace` of the same plan")
      ->check(CLI::ExistingFile);
  cmd->add_option("--local-trace-mm", o->local_trace_mm,
                  "With --align normal and no --trace: the local trace touches at (x +- d, y +- d)")
      ->check(CLI::Range(0.01, 20.0))
      ->capture_default_str();
  cmd->add_option("--max-tilt-deg", o->max_tilt_deg,
                  "With --align normal: refuse a normal tilted more")
      ->check(CLI::Range(0.01, 80.0))
      ->capture_default_str();
  cmd->callback([&ctx, o] {
    if (!o->trace.empty() && o->align != "normal")
      throw CLI::ValidationError("--trace",
                                 "gives the normals for --align normal, which is not set");
    ctx.action = [&ctx, o] { return map(ctx, *o); };
  });

}

}  // namespace palpctl
