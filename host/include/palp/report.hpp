// Reports (issue 22): every palp result as figures people read, the paper's way: force–depth
// curves with their fits, the stiffness heat map, Bode plots with the second-order fit, pressure
// against force. A report is a list of sections, each with Vega figures and tables; it is written
// as one self-contained HTML file (Vega inlined, the data embedded, opens offline) or as one
// standalone SVG per figure for papers.
//
// Library palp::report (palp_report): palp::experiments and nlohmann_json; the browser modules
// come from Debian's libjs-vega and the SVGs from Debian's node-vega at run time.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

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

}  // namespace palp::report
