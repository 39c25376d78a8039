// SPDX-License-Identifier: Apache-2.0
// palpctl report: a result as people read it, without a device. The SDK does the work
// (palp/report.hpp: make_report, write_report_html, write_report_svgs); docs/report.md says what
// each report shows.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "common.hpp"
#include "palp/error.hpp"
#if PALP_HAVE_HDF5
#include "palp/hdf5.hpp"
#endif
#include "palp/report.hpp"
#include "palp/result.hpp"

namespace palpctl {

namespace {

struct ReportCli {
  std::string input, out, svg_dir;
  bool overwrite = false;
};

int report_command(const Context& ctx, const ReportCli& o) {
  const palp::Overwrite ow = o.overwrite ? palp::Overwrite::yes : palp::Overwrite::no;
  // --svg's directory is checked before anything is written, so a refusal leaves no page either
  if (!o.svg_dir.empty() && std::filesystem::exists(std::filesystem::symlink_status(o.svg_dir))) {
    if (!o.overwrite)
      throw palp::ConfigError(o.svg_dir + " already exists; choose another --svg, or pass --overwrite to replace it");
    palp::check_replaceable(o.svg_dir);
  }
#if PALP_HAVE_HDF5
  if (palp::is_hdf5_file(o.input))
    throw palp::ConfigError(o.input + " is an HDF5 file; a report is made from the directory it was exported from " +
                            "(a map, result or trace directory)");
#endif
  const palp::report::Report r = palp::report::make_report(o.input);
  palp::report::write_report_html(o.out, r, ow);
  std::vector<std::filesystem::path> svgs;
  if (!o.svg_dir.empty()) svgs = palp::report::write_report_svgs(o.svg_dir, r, ow);
  std::size_t figures = 0;
  for (const auto& s : r.sections) figures += s.figures.size();
  if (ctx.json) {
    json files = json::array(), sections = json::array();
    for (const auto& f : svgs) files.push_back(f.string());
    for (const auto& s : r.sections) {
      json figs = json::array();
      for (const auto& f : s.figures) figs.push_back(f.id);
      sections.push_back({{"id", s.id}, {"title", s.title}, {"figures", figs}, {"tables", s.tables.size()}});
    }
    print_json({{"html", std::filesystem::absolute(o.out).lexically_normal().string()},
                {"title", r.title},
                {"svgs", files},
                {"sections", sections}});
  } else {
    std::cout << "wrote " << o.out << ": " << r.title << ", " << r.sections.size() << " section"
              << (r.sections.size() == 1 ? "" : "s") << ", " << figures << " figure" << (figures == 1 ? "" : "s")
              << "\n";
    if (!svgs.empty()) std::cout << "wrote " << svgs.size() << " SVG files in " << o.svg_dir << "\n";
  }
  return kOk;
}

}  // namespace

void add_report_command(CLI::App& app, Context& ctx) {
  auto o = std::make_shared<ReportCli>();
  auto* cmd = app.add_subcommand(
      "report",
      "Write a result as one self-contained HTML page of figures and tables (docs/report.md): it opens "
      "offline in any browser, with Vega (Debian's libjs-vega) and the data inside the file. INPUT is a map "
      "directory (map.json: the k_fd heat map with the soft and stiff rows and columns marked, each point's "
      "values on hover and its force-depth curves on a click, and the traced surface), a result directory "
      "(result.json: an indentation's force-depth curves, fits and parameters and its pressure channels, or "
      "an identification's Bode plots), or a trace (trace.json: the surface's heights and normals). A header "
      "gives the device, firmware, protocol, calibration and settings of the run. --svg DIR also writes each "
      "figure as a standalone SVG file for papers (needs node and Debian's node-vega; no browser).");
  cmd->add_option("input,--input", o->input, "The map directory, result directory or trace to report")->required();
  cmd->add_option("--out", o->out, "The HTML file to write (atomically)")->required();
  cmd->add_option("--svg", o->svg_dir,
                  "Also write every figure as DIR/<figure id>.svg (DIR is written whole, atomically)");
  cmd->add_flag("--overwrite", o->overwrite,
                "Replace --out (and --svg's directory) when palp wrote it; any other file is never replaced");
  cmd->callback([&ctx, o] { ctx.action = [&ctx, o] { return report_command(ctx, *o); }; });
}

}  // namespace palpctl
