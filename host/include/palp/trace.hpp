// SPDX-License-Identifier: Apache-2.0
// Surface tracing: the arm carries the probe over a plan's grid and, at every point, finds the
// zero-force contact point with a guarded approach (the paper's procedure: advance slowly along
// the probe axis until the coil has moved 0.2 mm, stop, record the 3D contact position), then the
// local normal and tilt from the neighbouring points.
//
//   palp::Probe probe(rig.probe_uri);
//   auto robot = palp::connect_robot(rig.robot_uri);
//   palp::TraceOptions options;
//   options.cancelled = [] { return g_sigint != 0; };  // Ctrl-C: stop cleanly
//   palp::TracedSurface s = palp::trace_surface(probe, *robot, rig, plan, options);
//
// Per point (README.md "Tracing" has the timeline):
//   1. move above the point (work-object frame, z = expected surface - clearance);
//   2. the probe holds rig.watch_current_A (the coil floats off its rear stop) and arms its
//      contact watch (rig.contact_threshold_m of coil motion), whose contact-output line is wired to
//      the robot's digital input rig.contact_input;
//   3. GUARDED_APPROACH along the tool's z at the approach speed, guards: host stop and that input
//      (the robot stops itself within its own cycle); on the probe's contact event the SDK writes
//      the stop request at once (the second path); it waits until the arm is stationary;
//   4. it reads the tool pose and the coil's stroke position, both at rest; the tip apex is the
//      TCP moved by the stroke along the approach axis, which makes stop latency irrelevant;
//   5. the detection force k_v * (coil push-back) has indented the surface a little: that
//      indentation comes from the plan's contact_E_star_Pa (Hertz sphere), else from the contact
//      stiffness measured during the approach itself (coil counts against arm travel between the
//      guard's latched pose and the rest pose); the zero-force apex is moved back by it;
//   6. retract by the clearance and go on.
// After the grid: normals by the finite-difference stencil of the neighbouring points, and the
// contact point moved from the apex to where the sphere of the tip's radius touches along that
// normal (iterated), so slope does not bias it.
//
// On cancel or on any error during the plan: stop the arm, zero the coil current, retract to the
// safe height, and return what was traced with `resume_index` (the first point not finished) and
// the reason; trace_surface(..., options.resume) continues from there without repeating a point.
#pragma once

#include <exception>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <optional>

#include "palp/probe.hpp"
#include "palp/rig.hpp"
#include "palp/robot.hpp"

namespace palp {

/// One traced grid point. What was measured at rest is in the robot's base frame; what
/// finish_surface derives from it is in the work-object frame (m).
struct TracePoint {
  int row = 0, column = 0;           ///< 1-based
  bool ok = false;
  std::string reason;                ///< why not ok ("no contact within 15.000 mm of travel")
  // measured, the arm and the coil at rest after the slow approach
  Pose tcp_at_rest;                  ///< base frame; the tool's z is the approach axis
  double stroke_at_rest_m = 0;       ///< the coil's stroke position (encoder): apex = TCP + s z
  double detection_force_N = 0;      ///< k_v times the coil's push-back at rest
  std::optional<double> contact_stiffness_N_per_m;  ///< measured on the approach, when it could be
  double overtravel_m = 0;           ///< arm travel from the guard's latch to rest
  int guard_fired = 0;               ///< proto::rb::GuardSource bits that stopped the approach
  // derived (finish_surface), work-object frame
  double x_m = 0, y_m = 0, z_m = 0;  ///< the zero-force contact point on the surface
  double apex_x_m = 0, apex_y_m = 0, apex_z_m = 0;  ///< the tip apex at zero force
  double normal[3] = {0, 0, 1};      ///< unit surface normal, into the specimen
  double tilt_rad = 0;               ///< angle between the normal and the work object's z
  double indentation_m = 0;          ///< the detection force's indentation, removed
};

struct TracedSurface {
  std::string plan_name;
  int rows = 0, columns = 0;
  Pose work_object;                  ///< in the robot's base frame
  double tip_radius_m = 2.5e-3;
  std::optional<double> contact_E_star_Pa;  ///< the plan's, for the indentation
  std::vector<TracePoint> points;    ///< row-major, rows * columns once complete
  std::size_t resume_index = 0;      ///< the first point not traced (== points.size())
  bool complete = false;
  bool normals_from_grid = false;    ///< false: a partial or failed grid, normals = the approach axis
  std::string stopped_because;       ///< empty when complete
  /// The error that stopped it (null when complete or cancelled), to handle by its kind with
  /// std::rethrow_exception (palpctl exits with that kind's code). Not in trace.json.
  std::exception_ptr stopped_error;
};

struct TraceProgress {
  std::size_t done = 0, total = 0;
  const TracePoint* last = nullptr;
  /// The trace so far (its points measured; normals not yet derived): save it here to survive
  /// a crash, and resume from it.
  const TracedSurface* surface = nullptr;
};

struct TraceOptions {
  /// Polled between steps: returning true stops the plan at the next safe moment (a Ctrl-C flag).
  std::function<bool()> cancelled;
  /// Called after every point, on the caller's thread.
  std::function<void(const TraceProgress&)> progress;
  /// Continue a trace that stopped: its points are kept and tracing starts at its resume_index.
  std::optional<TracedSurface> resume;
};

/// Traces plan's grid. Throws ConfigError before anything moves for a plan the rig cannot do (no
/// registered work object, another work object, a resume that belongs to another grid). Errors
/// during the plan (a point the arm cannot reach, a lost link, a tip touching at the safe
/// height) end it as described above: the result has complete = false and the error's text in
/// stopped_because. A point without contact is kept with ok = false and its reason; its contact
/// watch is stopped (the coil drops, the next point floats it again) and the plan goes on.
TracedSurface trace_surface(Probe& probe, Robot& robot, const Rig& rig, const Plan& plan,
                            const TraceOptions& options = {});

/// One touch of the surface with a guarded approach (as at each point of trace_surface).
struct Touch {
  bool ok = false;
  std::string reason;
  TracePoint at_rest;                ///< the measured part
};

/// Three-point touch-off: from each start pose (base frame, above the point, the tool's z along
/// the approach) touch the surface; the first point is the work object's origin, the second lies
/// on its +x axis, the third on its +y side; +z points along the approach, into the specimen.
/// contact_E_star_Pa: the surface's E* for the indentation correction (none: measured). Returns
/// the work object's pose in the base frame. Throws ConfigError when the points are collinear,
/// and any error of the probe or the robot after making the arm safe.
Pose touch_off(Probe& probe, Robot& robot, const Rig& rig, const Pose (&start)[3],
               std::optional<double> contact_E_star_Pa = std::nullopt,
               std::function<bool()> cancelled = {});

/// Derives the contact points, normals, tilts and indentations of a traced surface from what was
/// measured (the step trace_surface ends with; idempotent): with a complete grid of at least
/// 2 x 2 good points, normals by analysis::grid_normals iterated with the tip-radius correction
/// (analysis::contact_point, 3 passes); otherwise each point with its approach axis as normal.
void finish_surface(TracedSurface& surface);

/// Writes a traced surface as JSON in lab units (mm, deg, N; docs/rig-and-plan.md "Trace files"),
/// atomically (a temporary file renamed over the old one), so a crash never leaves half a file.
void save_trace(const std::filesystem::path& file, const TracedSurface& surface);
/// Reads one back. Throws ConfigError "file: problem" for anything malformed.
TracedSurface load_trace(const std::filesystem::path& file);

}  // namespace palp
