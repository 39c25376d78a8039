// SPDX-License-Identifier: Apache-2.0
// The live view's page (palpctl monitor --plot): one self-contained HTML document with Debian's
// dygraphs (libjs-dygraphs) inlined, so the page needs nothing but its own server's /events.
//
// What the page shows: three stacked plots against device time (current i_cmd and i in A,
// position z in mm, pressures p1..p6 in Pa) with legends, a Pause/Resume button (pauses the view;
// the data keeps arriving and the device is untouched), a "last N s" window selector, markers for
// gaps (orange, with the number of samples lost) and faults or state changes (red for a fault,
// grey for a state change), and a status line (state, fault, samples/s, samples lost, the view's
// refresh rate). The events it reads are documented in live_stream.hpp.
//
// For tests and the curious, window.palpLive holds the page's counters: sampleMessages,
// points, redraws, paused, markers ([{kind, t_s, label}]), markersDrawn, status, viewHz, and
// panels (current, z, p: each with rows [[t_s, values...]] as plotted).
#pragma once

#include <string>

namespace palpctl {

/// Debian's dygraphs files, read whole at run time.
struct DygraphsFiles {
  std::string js, css;
};

/// Where the files are: /usr/share/javascript/dygraphs, or $PALP_DYGRAPHS_DIR when set.
std::string dygraphs_dir();

/// Reads dygraph.min.js and dygraph.min.css from dygraphs_dir() (each bounded to 4 MiB). Throws
/// palp::Error naming the file, the problem and the package (libjs-dygraphs) when one is missing.
DygraphsFiles load_dygraphs();

/// The page with the library inlined.
std::string live_page_html(const DygraphsFiles& dygraphs);

}  // namespace palpctl
