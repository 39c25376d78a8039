// SPDX-License-Identifier: Apache-2.0
// Stiffness mapping (issue 6; the paper's §V): for each point of a plan, touch the surface with a
// guarded approach (trace.hpp), indent it with the quasi-static staircase (indent.hpp),
// retract, move on; then the stiffness map, the surface it was measured on, and the soft and
// stiff lines found in it.
//
//   palp::MapOptions o;                                   // 2D protocol: 0.5 -> 3 A every 25 ms, x3
//   o.cancelled = [] { return g_sigint != 0; };
//   palp::StiffnessMap m = palp::map_plan(probe, *robot, rig, plan, "results/pad-map", o);
//   palp::MapAnalysis a = palp::analyze_map(m);           // k_fd per point, soft columns, ...
//
// The directory (docs/result-format.md "Maps"): map.json (the plan, the settings, every point's
// surface and stiffness, `resume_index`), written atomically after every point, and
// points/r<row>_c<column>/, one indentation result directory per point (result.hpp). A map that
// stopped (Ctrl-C, a crash, an error) resumes with MapOptions::resume from the first point not
// finished: no point is lost or repeated (a point whose result directory was written but not yet
// recorded in map.json is indented again and its directory replaced). An adaptive map
// (MapOptions::adaptive) measures only some points of the grid, in the planner's order, and
// map.json lists those (an "adaptive" object holds the planner's options).
//
// At each point the probe touches with the coil floating at the ramp's start current (the
// paper's I_c = 0.5 A, where the coil exerts no force at contact), so the ramp that follows
// starts in contact, as the paper's protocol does; indent() zeroes the pressures with the coil at
// 0 A first and floats it again.
#pragma once

#include <exception>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "palp/analysis/adaptive_grid.hpp"
#include "palp/indent.hpp"
#include "palp/map_dynamic.hpp"
#include "palp/trace.hpp"

namespace palp {

struct MapPoint {
  int row = 0, column = 0;             ///< 1-based
  TracePoint surface;                  ///< the touch (measured part; z etc. once finished)
  bool indented = false;
  std::string reason;                  ///< why not indented / no stiffness
  std::optional<double> k_fd_N_per_m;  ///< the paper's Fig. 6 stiffness, (F_o(0.75) - F_o(0.25)) / 0.5 mm
  std::string k_fd_reason;
  std::optional<double> delta0_m, k_tangent_N_per_m;
  std::string result_dir;              ///< relative to the map's directory ("points/r1_c1")
  // dynamic (map_dynamic.hpp): the identification after the ramp, when the map is dynamic
  std::string dynamic_dir;             ///< "points/r1_c1_dynamic"; empty when not identified
  DynamicPoint dynamic;
  // alignment (MapOptions::align_to_normal): the tool's axis at this point's touch and ramp
  std::string aligned_by = "none";     ///< "none" (the work object's z), "trace" or "local trace"
  double tilt_rad = 0;                 ///< the tool's z from the work object's z, as used
  std::vector<double> tool_axis;       ///< aligned: the tool's z (unit, work-object frame)
  /// Aligned: the current added to the touch's and the ramp's (and the analysis' I_c and I_0) so
  /// that the tilted coil floats and works where it does upright (its weight along the axis
  /// changes with the tilt; K_f changes with the stroke position): k_v (s_upright - s) / K_f.
  double coil_offset_A = 0;
};

struct StiffnessMap {
  std::string plan_name;
  int rows = 0, columns = 0;
  IndentationSettings settings;
  TracedSurface surface;               ///< the touches, as a traced surface (normals once complete)
  std::vector<MapPoint> points;        ///< in measurement order (row-major unless adaptive)
  // dynamic (map_dynamic.hpp): the identification settings of a dynamic map, none otherwise
  std::optional<IdentificationSettings> dynamic;
  std::size_t resume_index = 0;
  bool complete = false;
  std::string stopped_because;
  std::optional<double> max_force_N;   ///< MapOptions::max_force_N the map ran with (map.json)
  /// The error that stopped the map (null when complete or cancelled), to handle by its kind:
  /// std::rethrow_exception (palpctl exits with that kind's code). Not in map.json.
  std::exception_ptr stopped_error;
  // adaptive: the planner's options (absent: the regular grid, every point) and why it ended
  std::optional<analysis::AdaptiveGridOptions> adaptive;
  std::string adaptive_ended;          ///< "budget" or "converged" once complete
};

struct MapProgress {
  std::size_t done = 0, total = 0;
  const MapPoint* last = nullptr;
  std::string phase;                   ///< "touch", "indent", "retract"
};

struct MapOptions {
  IndentationSettings settings = IndentationSettings::preset(IndentationPreset::two_d);
  std::function<void(const MapProgress&)> progress;
  std::function<bool()> cancelled;
  bool resume = false;                 ///< continue the map in the directory
  // adaptive: measure only the points the planner chooses (analysis/adaptive_grid.hpp): a coarse
  // space-filling design, then refinement where neighbours differ, within a budget. A resumed
  // map continues as map.json says it started (these options, if given, must be the same).
  std::optional<analysis::AdaptiveGridOptions> adaptive;
  // depth sensitivity (docs/depth-sensitivity.md): the ramp stops at this object force, N; each
  // point's top current from the depth the previous point reached (force_limit.hpp); refused
  // (ConfigError) beyond the device's current clamp or I2t margin. Absent: settings.stop_A.
  std::optional<double> max_force_N;
  // dynamic (map_dynamic.hpp): identify the contact at every point after the ramp
  MapDynamicOptions dynamic;
  // alignment (issue 24): at each point the tool's z along the surface normal, started above the
  // point's tangent plane along that normal, so the guarded approach, the ramp and the back-off
  // all run normal to the surface (docs/normal-aligned-maps.md)
  bool align_to_normal = false;
  /// The normals to align with: a trace of the same plan in the same work object (trace_surface,
  /// complete, normals from its grid). None: a local trace at each point, four touches along the
  /// work object's z at (x +- d, y +- d), d = local_trace_offset_m, their tangent plane.
  std::optional<TracedSurface> align_trace;
  double local_trace_offset_m = 2e-3;
  /// A normal tilted more from the work object's z is refused: ConfigError before anything moves
  /// for a trace's, the point's reason (not indented) for a local trace's.
  double max_tilt_rad = 0.5235987755982988;  // 30 deg
};

/// Maps plan's grid into `dir` (created; ConfigError, before anything moves, if it holds a map and
/// resume is off, or if the result directory of a point still to map exists and palp did not
/// write it: check_replaceable, result.hpp).
/// Errors and cancellation end the map as trace_surface does (arm stopped, coil at 0 A, raised
/// to the safe height) and return it with stopped_because.
StiffnessMap map_plan(Probe& probe, Robot& robot, const Rig& rig, const Plan& plan,
                      const std::filesystem::path& dir, const MapOptions& options = {});

/// Reads a map directory's map.json (ConfigError "file: problem").
StiffnessMap load_map(const std::filesystem::path& dir);
/// Writes `m` as dir/map.json (dir created), atomically (a temporary file renamed over it), as
/// map_plan does after every point: for tools and tests that assemble a map from result
/// directories (write_result) of their own. load_map reads it back.
void save_map(const std::filesystem::path& dir, const StiffnessMap& m);
/// map.json's document (what save_map writes) and back (what load_map reads; ConfigError
/// "where: problem"): for readers of a map kept elsewhere, such as an HDF5 file (hdf5.hpp).
nlohmann::json map_to_json(const StiffnessMap& m);
StiffnessMap map_from_json(const nlohmann::json& j, const std::string& where);

/// The map's analysis: the stiffness grid and the lines (rows, columns) that stand out.
struct MapAnalysis {
  int rows = 0, columns = 0;
  std::vector<std::optional<double>> k_N_per_m;  ///< row-major; absent where a point failed
  /// Over the points present; on an adaptive map with points not measured the additive fit's
  /// line means instead (analysis::line_means), which the sampling does not bias.
  std::vector<double> column_mean_N_per_m, row_mean_N_per_m;
  double median_N_per_m = 0;
  /// Columns / rows whose mean is at least `contrast` below (soft) or above (stiff) the median
  /// of all columns' / rows' means (1-based).
  std::vector<int> soft_columns, stiff_columns, soft_rows, stiff_rows;
  double contrast = 0.1;
  // adaptive: which points were measured (row-major; absent k where false is "not measured")
  std::vector<bool> measured;
};

/// k per point from the map (k_fd, or re-analysed from each point's recording when
/// reanalyse is set, with `params`), and the soft/stiff lines at `contrast` (0.1: 10 %).
MapAnalysis analyze_map(const StiffnessMap& map, double contrast = 0.1);

}  // namespace palp
