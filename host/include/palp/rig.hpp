// SPDX-License-Identifier: Apache-2.0
// The rig and the plan (issue 5): what is bolted together (rig.json) and what to trace
// (plan.json). Schemas, units and complete examples: docs/rig-and-plan.md.
//
//   palp::Rig rig = palp::load_rig("rig.json");      // robot, probe, tool, speeds, contact line
//   palp::Plan plan = palp::load_plan("plan.json");  // a grid in a named work-object frame
//   for (int r = 0; r < plan.grid.rows; ++r)
//     for (int c = 0; c < plan.grid.columns; ++c) { auto [x, y] = plan.point_m(r, c); ... }
//
// The files are JSON in lab units with the unit in every key (mm, mm/s, deg, A, Pa); the
// structs are SI (m, m/s, rad, A, Pa). Unknown keys, missing required keys, wrong types and
// out-of-range values are palp::ConfigError "file: key: problem"; a JSON syntax error is
// "file:line:column: problem" (the character where the parser stopped).
//
// Work-object frame (analysis/surface.hpp register_work_object): origin and x axis from the
// touch-off, +z INTO the specimen (along the probe's approach), y = z x x. The simulated world's
// work object is the phantom frame.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "palp/robot.hpp"

namespace palp {

/// A registered work object: its frame as a pose in the robot's base frame.
struct WorkObject {
  std::string name;
  Pose pose;  ///< origin in m, KUKA ZYX angles in rad
};

/// The rig: robot, probe, tool and the guarded approach's settings (SI).
struct Rig {
  std::string robot_uri;                   ///< "modbus://host:port" (required)
  std::string probe_uri;                   ///< "usb://", "sim://host:port", ... (required)
  int tool_id = 1;                         ///< the bridge's tool slot for the probe, 1..15
                                           ///< (proto::rb::kMaxTool, the bridge's set_tool range)
  Pose tool_tcp;                           ///< the tip apex at stroke origin, on the flange
  double safe_height_m = 10e-3;            ///< travel height above the work object's surface
                                           ///< (along its -z), > 0 (required in the file)
  double approach_speed_m_per_s = 1e-3;    ///< guarded approach speed
  double travel_speed_m_per_s = 0.02;      ///< linear moves between points
  int contact_input = 1;                   ///< robot digital input wired to the contact line, 1..16
                                           ///< (proto::rb::kMaxDigitalInput)
  double contact_threshold_m = 0.2e-3;     ///< coil motion that means contact (paper: 200 counts)
  /// Coil current held during the approach so that the coil floats clear of both end stops and
  /// a touch pushes it back. The paper's contact threshold I_c = 0.5 A is the float current
  /// (palp-sim: the coil floats at 25 mm of its 34 mm stroke); 0.6 A floats it 6.6 mm further
  /// out, still short of the front stop, so the 0.2 mm push comes with a firmer hold.
  double watch_current_A = 0.6;
  double max_approach_m = 10e-3;           ///< give up after this much approach travel
  double tip_radius_m = 2.5e-3;            ///< the probe tip's sphere (paper: PLA, R = 2.5 mm)
  std::optional<WorkObject> work_object;   ///< written by the touch-off

  /// ConfigError "rig: safe_height_m is nan, not a finite number" for a number that is NaN or
  /// infinite, else "rig: <key>: <problem>" for one outside the range rig.json takes (the same
  /// table as the reader). trace_surface, touch_off, map_plan and save_rig call it first.
  void validate() const;
};

/// The plan's grid in the work object (SI). Row r (0-based) is at y = y0 + r pitch_y, column c
/// at x = x0 + c pitch_x; points are visited row-major.
struct PlanGrid {
  int rows = 1, columns = 1;                         ///< 1..1000 each
  double x0_m = 0.0, y0_m = 0.0;                     ///< row 0, column 0
  double pitch_x_m = 0.0, pitch_y_m = 0.0;           ///< along x (columns), y (rows)
};

/// A grid of points to trace in a named work-object frame (SI).
struct Plan {
  std::string name;
  std::string work_object;                           ///< must match the rig's work object
  PlanGrid grid;
  std::optional<double> contact_E_star_Pa;           ///< for the indentation correction
  std::optional<double> approach_speed_m_per_s;      ///< overrides the rig's
  /// x of column c, y of row r, (x, y) of row r, column c in the work object, m (0-based).
  /// Throws ConfigError outside the grid.
  double x_m(int column) const;
  double y_m(int row) const;
  std::pair<double, double> point_m(int row, int column) const;
  int point_count() const { return grid.rows * grid.columns; }
  /// ConfigError "plan <name>: grid.pitch_x_m is nan, not a finite number" for a number that is
  /// NaN or infinite, or a grid outside 1..1000 x 1..1000 (trace_surface and map_plan call it).
  void validate() const;
};

/// Read a rig file. Throws ConfigError (also when the file cannot be read).
Rig load_rig(const std::filesystem::path& file);
/// Parse rig JSON text; source names it in errors.
Rig parse_rig(std::string_view json, std::string_view source);
/// Write a rig file (atomically: a temporary file renamed over it), lab units, the same keys.
/// Throws ConfigError when it cannot be written.
void save_rig(const std::filesystem::path& file, const Rig& rig);
/// The rig as JSON text (what save_rig writes).
std::string rig_to_json(const Rig& rig);

/// Read a plan file. Throws ConfigError (also when the file cannot be read).
Plan load_plan(const std::filesystem::path& file);
/// Parse plan JSON text; source names it in errors.
Plan parse_plan(std::string_view json, std::string_view source);

}  // namespace palp
