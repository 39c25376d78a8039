// SPDX-License-Identifier: Apache-2.0
// Reports (issue 22): every palp result as figures people read, the paper's way: force–depth
// curves with their fits, the stiffness heat map, Bode plots with the second-order fit, pressure
// against force. A report is a list of sections, each with Vega figures and tables; it is written
// as one self-contained HTML file (Vega inlined, the data embedded, opens offline) or as one
// standalone SVG per figure for papers.
//
//
//   palp::report::Report r = palp::report::make_report("results/pad-map");  // a map directory
//   palp::report::write_report_html("pad-map.html", r);      // one file, opens offline
//   palp::report::write_report_svgs("pad-map-figures", r);   // <figure id>.svg per figure
//
// Library palp::report (palp_report): palp::experiments and nlohmann_json; the browser modules
// come from Debian's libjs-vega and the SVGs from Debian's node-vega at run time (docs/report.md).
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "palp/recording.hpp"

namespace palp::report {

/// One plot: a complete Vega 5 specification with its data embedded, so that it renders alone
/// (an SVG file) or inside the HTML page. Axis titles carry their units ("δ (mm)", "F_o (N)").
struct Figure {
  std::string id;       ///< unique within a report; the SVG's file stem ("indentation-force-depth")
  std::string title;    ///< the heading above the plot
  std::string caption;  ///< one or two sentences under it: what is drawn, how it was computed
  nlohmann::json spec;  ///< the Vega specification
};

/// A table of numbers already formatted for people (units in the column headers).
struct Table {
  std::string id, title;
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
  std::string caption;
};

/// One part of a report: an indentation, a map, an identification, a trace, the pressures.
struct Section {
  std::string id, title;
  std::string text;  ///< a short paragraph before the figures (plain text), may be empty
  std::vector<Figure> figures;
  std::vector<Table> tables;
};

/// A whole report: a header that says what was measured with what, and the sections.
struct Report {
  std::string title;  ///< "Stiffness map: pad 9 x 9"
  std::string input;  ///< the path the report was made from, as given
  /// The header's lines, label and value, in order: the device, firmware, protocol, calibration
  /// and the settings of the run ("Device", "SYNTH-0001 (synthetic)").
  std::vector<std::pair<std::string, std::string>> header;
  std::vector<Section> sections;
};

/// The report of `input`, chosen by what it is:
///   a map directory (map.json)                 the map (map_section), its header from map.json
///                                              and the first point's result.json
///   a result directory (result.json)           by its experiment: "indentation" (the curves and
///                                              the pressure channels), "identification"
///   a trace file, or a directory with trace.json  the traced surface
/// ConfigError naming `input` when it is none of these (or is missing); the readers' errors
/// (RecordingError, ConfigError naming the file) propagate, and so do the builders' for a result
/// they cannot draw.
Report make_report(const std::filesystem::path& input);

/// How every report's HTML file begins; an existing file is replaced (Overwrite::yes) only when
/// it begins so (palp wrote it).
inline constexpr const char* kReportHtmlHead = "<!DOCTYPE html>\n<!-- palp report";

/// The report as one self-contained HTML page: the Vega modules of Debian's libjs-vega inlined
/// (read from /usr/share/javascript, or $PALP_JS_DIR), each figure's spec embedded as JSON and
/// drawn as SVG in the browser, the tables as HTML. ConfigError naming the missing file and its
/// Debian package when a module is absent.
std::string report_html(const Report& report);

/// report_html written to `file` atomically (a hidden temporary sibling renamed into place; its
/// parent directory created). An existing `file` is refused (ConfigError) without Overwrite::yes,
/// and with it unless it begins with kReportHtmlHead. RecordingError when it cannot be written.
void write_report_html(const std::filesystem::path& file, const Report& report,
                       Overwrite overwrite = Overwrite::no);

/// One standalone SVG per figure, `<dir>/<figure id>.svg`, rendered by host/report/vega-to-svg.js
/// with Debian's node (nodejs) and node-vega (no browser; text widths are estimated). `dir` is
/// written as a result directory is (result.hpp: atomically, with the list of its files, and
/// replaced with Overwrite::yes only when palp wrote it). Returns the files written, in figure
/// order. ConfigError when node or the script cannot be found, RecordingError with Vega's
/// message when a figure does not render.
std::vector<std::filesystem::path> write_report_svgs(const std::filesystem::path& dir,
                                                     const Report& report,
                                                     Overwrite overwrite = Overwrite::no);

}  // namespace palp::report
