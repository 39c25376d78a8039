// SPDX-License-Identifier: Apache-2.0
// palpctl trace: trace a plan's grid with the arm (guarded approaches), write trace.json, resume
// after Ctrl-C or a crash. palpctl touch-off: register the work object with three touches.
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>

#include "common.hpp"
#include "palp/robot.hpp"
#include "palp/trace.hpp"

namespace palpctl {

namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;

struct TraceCli {
  std::string rig, plan, out_dir = "trace";
  bool resume = false;
};

json point_row(const palp::TracePoint& p) {
  if (!p.ok) return {{"row", p.row}, {"column", p.column}, {"z_mm", nullptr}, {"z_mm_reason", p.reason}};
  return {{"row", p.row},          {"column", p.column},         {"x_mm", p.x_m * 1e3},
          {"y_mm", p.y_m * 1e3},   {"z_mm", p.z_m * 1e3},        {"tilt_deg", p.tilt_rad * kDeg},
          {"detection_force_N", p.detection_force_N}};
}

int trace(const Context& ctx, const TraceCli& o) {
  palp::Rig rig = palp::load_rig(o.rig);
  const palp::Plan plan = palp::load_plan(o.plan);
  const std::filesystem::path dir(o.out_dir);
  const std::filesystem::path file = dir / "trace.json";
  palp::TraceOptions options;
  if (o.resume) {
    options.resume = palp::load_trace(file);
    if (options.resume->complete) {
      std::cerr << "palpctl: " << file.string() << " is already complete; nothing to resume\n";
      return kOk;
    }
  } else if (std::filesystem::exists(file)) {
    throw palp::ConfigError(file.string() + " exists: pass --resume to continue it, or another --out-dir");
  }
  std::filesystem::create_directories(dir);

  palp::Probe probe = ctx.connect(rig.probe_uri);
  if (o.resume) recover_for_resume(probe);
  auto robot = palp::connect_robot(rig.robot_uri);
  catch_interrupts();
  options.cancelled = [] { return interrupted(); };
  const bool show = !ctx.json;
  Progress progress("trace", static_cast<std::uint64_t>(plan.grid.rows * plan.grid.columns), show, "points");
  options.progress = [&](const palp::TraceProgress& p) {
    palp::save_trace(file, *p.surface);  // after every point: a crash loses at most the current one
    progress.update(p.done);
  };
  palp::TracedSurface s = palp::trace_surface(probe, *robot, rig, plan, options);
  progress.finish(s.resume_index);
  palp::save_trace(file, s);

  json j = {{"plan", s.plan_name},
            {"rows", s.rows},
            {"columns", s.columns},
            {"complete", s.complete},
            {"points_done", s.resume_index},
            {"trace_file", file.string()}};
  if (!s.complete) j["stopped_because"] = s.stopped_because;
  json pts = json::array();
  for (const auto& p : s.points) pts.push_back(point_row(p));
  j["points"] = pts;
  if (ctx.json) {
    print_json(j);
  } else {
    std::printf("%s: %d x %d, %zu points traced, written to %s\n", s.plan_name.c_str(), s.rows, s.columns,
                s.resume_index, file.string().c_str());
    std::printf("surface height z (mm, work-object frame, +z into the specimen):\n      ");
    for (int c = 1; c <= s.columns; ++c) std::printf("  col %-3d", c);
    std::printf("\n");
    for (int r = 1; r <= s.rows; ++r) {
      std::printf("row %-2d", r);
      for (int c = 1; c <= s.columns; ++c) {
        const std::size_t k = static_cast<std::size_t>((r - 1) * s.columns + (c - 1));
        if (k < s.points.size() && s.points[k].ok)
          std::printf(" %8.3f", s.points[k].z_m * 1e3);
        else
          std::printf(" %8s", k < s.points.size() ? "failed" : "-");
      }
      std::printf("\n");
    }
  }
  if (!s.complete) {
    std::cerr << "palpctl: trace stopped (" << s.stopped_because << ") after " << s.resume_index
              << " points; the arm is at the safe height and the coil current is zero.\n"
              << "resume with: palpctl trace --rig " << o.rig << " --plan " << o.plan << " --out-dir "
              << o.out_dir << " --resume\n";
    if (interrupted()) return kInterrupted;
    // the error that stopped it decides the exit code, as it would had it not been caught
    if (s.stopped_error) std::rethrow_exception(s.stopped_error);
    return kRuntime;
  }
  return kOk;
}

struct TouchOffCli {
  std::string rig, name = "touch_off";
  std::vector<double> p[3];
  std::vector<double> abc_deg{0, 0, 180};
  double e_star_Pa = 0;
};

int touch_off(const Context& ctx, const TouchOffCli& o) {
  palp::Rig rig = palp::load_rig(o.rig);
  palp::Probe probe = ctx.connect(rig.probe_uri);
  auto robot = palp::connect_robot(rig.robot_uri);
  catch_interrupts();
  palp::Pose start[3];
  for (int k = 0; k < 3; ++k)
    start[k] = palp::Pose{o.p[k][0] * 1e-3, o.p[k][1] * 1e-3, o.p[k][2] * 1e-3,
                          o.abc_deg[0] / kDeg, o.abc_deg[1] / kDeg, o.abc_deg[2] / kDeg};
  std::optional<double> e_star;
  if (o.e_star_Pa > 0) e_star = o.e_star_Pa;
  const palp::Pose frame = palp::touch_off(probe, *robot, rig, start, e_star, [] { return interrupted(); });
  rig.work_object = palp::WorkObject{o.name, frame};
  palp::save_rig(o.rig, rig);
  const json j = {{"work_object", o.name},
                  {"frame_mm_deg", {frame.x_m * 1e3, frame.y_m * 1e3, frame.z_m * 1e3, frame.a_rad * kDeg,
                                    frame.b_rad * kDeg, frame.c_rad * kDeg}},
                  {"rig_file", o.rig}};
  if (ctx.json)
    print_json(j);
  else
    print_text(j);
  return kOk;
}

}  // namespace

void add_trace_command(CLI::App& app, Context& ctx) {
  auto t = std::make_shared<TraceCli>();
  auto* cmd = app.add_subcommand(
      "trace",
      "Trace a plan's grid with the arm: at every point a guarded approach finds the zero-force "
      "contact point; then normals and tilts from the neighbours. Writes OUT_DIR/trace.json after "
      "the run; Ctrl-C stops the arm, zeroes the coil current, retracts to the safe height and "
      "keeps what was traced (continue with --resume).");
  cmd->add_option("--rig", t->rig, "rig.json: robot and probe URIs, tool, safe height, speeds, work object")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--plan", t->plan, "plan.json: the grid in the work-object frame (mm)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out-dir", t->out_dir, "Directory for trace.json")->capture_default_str();
  cmd->add_flag("--resume", t->resume, "Continue OUT_DIR/trace.json from its first unfinished point");
  cmd->callback([&ctx, t] { ctx.action = [&ctx, t] { return trace(ctx, *t); }; });

  auto o = std::make_shared<TouchOffCli>();
  auto* to = app.add_subcommand(
      "touch-off",
      "Register the work object with three guarded touches: P1 is its origin, P2 lies on its +x "
      "axis, P3 on its +y side; +z points along the approach, into the specimen. Each --pN-mm is "
      "the TCP's start above the point, robot base frame. Writes the frame into the rig file.");
  to->add_option("--rig", o->rig, "rig.json (its work_object is replaced)")->required()->check(CLI::ExistingFile);
  to->add_option("--p1-mm", o->p[0], "TCP start above the origin: x y z in mm, base frame")->expected(3)->required();
  to->add_option("--p2-mm", o->p[1], "TCP start above a point on +x")->expected(3)->required();
  to->add_option("--p3-mm", o->p[2], "TCP start above a point on the +y side")->expected(3)->required();
  to->add_option("--abc-deg", o->abc_deg, "TCP orientation A B C in deg for the touches (tool z = approach)")
      ->expected(3)
      ->capture_default_str();
  to->add_option("--name", o->name, "Name of the work object")->capture_default_str();
  to->add_option("--contact-E-star-Pa", o->e_star_Pa,
                 "The surface's E* for the detection-force correction (0: measure it on the approach)")
      ->check(kNonNegative);
  to->callback([&ctx, o] { ctx.action = [&ctx, o] { return touch_off(ctx, *o); }; });
}

}  // namespace palpctl
