// SPDX-License-Identifier: Apache-2.0
// Where map_plan's touch at a point starts and along which axis (map.hpp, MapOptions' alignment
// block): the tool's z along the work object's z, or along the surface normal from a trace or
// from a local trace of four touches around the point.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "palp/identification.hpp"
#include "palp/map.hpp"
#include "toucher.hpp"

namespace palp::detail {

/// The start of one point's touch.
struct MapAim {
  bool ok = true;
  std::string reason;               ///< why there is no touch (the local trace found no surface)
  Pose start;                       ///< the TCP before the guarded approach (base frame)
  std::string aligned_by = "none";  ///< MapPoint::aligned_by
  double tilt_rad = 0;              ///< the tool's z from the work object's z
  std::vector<double> tool_axis;    ///< aligned: the tool's z (unit, work-object frame)
};

/// The settings with every current (the ramp's start and top, the analysis' I_c and I_0) raised
/// by offset_A: the ramp of a tilted coil floated with Toucher's tilt compensation.
IndentationSettings with_current_offset(IndentationSettings s, double offset_A);
/// The same for a dynamic map's identification at that point: its bias and I_c.
IdentificationSettings with_current_offset(IdentificationSettings s, double offset_A);

class MapAligner {
 public:
  MapAligner(Toucher& toucher, const Rig& rig, const Plan& plan, const MapOptions& options)
      : toucher_(toucher), rig_(rig), plan_(plan), o_(options) {}
  /// Checks the alignment options, and a trace against the plan and the rig (ConfigError naming
  /// the problem): before anything moves, once the rig has a work object and the toucher has it.
  void check() const;

  /// The start for the plan's point (row, column), 1-based, with the floating tip at the safe
  /// height: unaligned, clearance_m above the point along the work object's z; aligned, that
  /// far back along the normal from where the tangent plane meets the plan's (x, y). A local
  /// trace moves the arm (its touches, each followed by a rise to clearance_m).
  MapAim aim(int row, int column, double clearance_m);

 private:
  struct Plane {
    double point[3], normal[3];  // work-object frame; the normal unit, into the specimen
  };
  std::optional<Plane> local_plane(double x, double y, double clearance, std::string& why);

  Toucher& toucher_;
  const Rig& rig_;
  const Plan& plan_;
  const MapOptions& o_;
};

}  // namespace palp::detail
