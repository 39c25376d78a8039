// SPDX-License-Identifier: Apache-2.0
// The live view's feed (palpctl monitor --plot): drains a started stream kPushHz times a second
// and broadcasts it to the page's server-sent-events clients, until Ctrl-C or the time is up.
//
// Events (each a one-line JSON object, lab units in every key):
//   samples  {"t_s": [...], "i_cmd_A": [...], "i_A": [...], "z_mm": [...],
//             "p_Pa": [[p1...], ..., [p6...]]}   every push, possibly with no points.
//            Points are means over bins of samples (about kPointsPerS points per second of
//            signal); a bin never spans a gap, and a gap is a point with null values at the
//            device time of its first missing sample, so a plotted line breaks there.
//   gap      {"t_device_s", "count", "source"}   each palp::Gap of the stream
//   state    {"t_device_s", "state", "fault", "previous_state", "previous_fault"}
//            when probe.status() shows a new state or fault (checked kStatusHz times a second)
//   status   {"t_device_s", "state", "fault", "program", "samples_per_s", "samples_lost",
//             "gaps", "rate_Hz", "points_per_s", "push_Hz", "clients"}   kStatusHz times a second
#pragma once

#include <cstdint>

#include "live_server.hpp"
#include "palp/probe.hpp"

namespace palpctl {

struct LiveStreamOptions {
  double seconds = 0;     ///< 0: until Ctrl-C
  double rate_Hz = 1000;  ///< the stream's sample rate (configured by the caller)
};

/// What a live view saw, for the closing line.
struct LiveStreamTotals {
  std::uint64_t samples = 0, samples_lost = 0, gaps = 0, pushes = 0;
  double seconds = 0;
};

inline constexpr double kPushHz = 30;      ///< samples events per second
inline constexpr double kPointsPerS = 250;  ///< plotted points per second of signal, at most
inline constexpr double kStatusHz = 5;     ///< status polls (and status events) per second

/// Feeds the server from the probe's started stream until interrupted() or options.seconds.
LiveStreamTotals run_live_stream(palp::Probe& probe, LiveServer& server,
                                 const LiveStreamOptions& options);

}  // namespace palpctl
