// SPDX-License-Identifier: Apache-2.0
// palpctl export: a map or a result directory as one dataset file, without a device.
//   export --format csv INPUT --out FILE   the tidy CSV (palp/tidy_csv.hpp, docs/result-format.md)
//   export --format hdf5 INPUT --out FILE  a recording, a result directory, an identification or a
//                                          map as one HDF5 file (palp/hdf5.hpp,
//                                          docs/hdf5-format.md; export_hdf5.cpp)
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "common.hpp"
#include "export_hdf5.hpp"
#include "palp/error.hpp"
#include "palp/tidy_csv.hpp"

namespace palpctl {

namespace {

struct ExportCli {
  std::string format, input, out;
  bool overwrite = false;
};

int export_command(const Context& ctx, const ExportCli& o) {
  if (o.format == "hdf5") return export_hdf5(ctx, o.input, o.out, o.overwrite);
  if (o.format != "csv")
    throw palp::ConfigError("--format " + o.format + ": unknown; the formats there are: csv, hdf5");
  if (!o.overwrite && std::filesystem::exists(std::filesystem::symlink_status(o.out)))
    throw palp::ConfigError(o.out + " already exists; choose another --out, or pass --overwrite to replace it");
  const palp::TidyCsvExport e =
      palp::export_tidy_csv(o.input, o.out, o.overwrite ? palp::Overwrite::yes : palp::Overwrite::no);
  for (const std::string& d : e.damaged)
    std::cerr << "palpctl: export: a damaged point (its row gives this in point_reason; the export went on): " << d
              << "\n";
  if (ctx.json) {
    json damaged = json::array();
    for (const std::string& d : e.damaged) damaged.push_back(d);
    print_json({{"file", o.out}, {"format", "csv"}, {"rows", e.rows}, {"points", e.points}, {"damaged", damaged}});
  } else {
    std::cout << "wrote " << o.out << ": " << e.rows << " rows for " << e.points << " point"
              << (e.points == 1 ? "" : "s") << (e.damaged.empty() ? "" : ", " + std::to_string(e.damaged.size()) + " damaged")
              << "\n";
  }
  return kOk;
}

}  // namespace

void add_export_command(CLI::App& app, Context& ctx) {
  auto o = std::make_shared<ExportCli>();
  auto* cmd = app.add_subcommand(
      "export",
      "Export a map directory (map.json, points/) or one result directory as a dataset file. "
      "--format csv: one tidy table, a header line and one row per point and repetition (row, column, "
      "rep, the position in mm, each repetition's stiffness and fit keys in lab units, a <key>_reason "
      "beside every key that may be empty), that pandas.read_csv(f) or MATLAB readtable(f) read in "
      "one line (docs/result-format.md \"The tidy CSV\"). A damaged point does not stop the export: "
      "its row says why and palpctl names it on stderr. --format hdf5: a map directory, a result directory "
      "(an indentation, or a sweep's or free-air run's identification with its frequency response) or a "
      "recording (run.csv or run.h5) as one HDF5 file: the samples as typed, compressed columns with "
      "their units, result.json and map.json whole, the map's k_fd grid and soft/stiff lines, a group per "
      "point and per repetition (docs/hdf5-format.md). A damaged point of a map is named on stderr and "
      "kept in the file as lost; the other points are written.");
  cmd->add_option("--format", o->format, "csv or hdf5")->required();
  cmd->add_option("input,--input", o->input,
                  "The map's directory or a result directory (hdf5: also an identification's "
                  "result directory or a recording)")
      ->required();
  cmd->add_option("--out", o->out, "The file to write (atomically)")->required();
  cmd->add_flag("--overwrite", o->overwrite,
                "Replace --out's file when palp wrote it (a tidy CSV or an HDF5 file palp "
                "exported); any other file is never replaced");
  cmd->callback([&ctx, o] { ctx.action = [&ctx, o] { return export_command(ctx, *o); }; });
}

}  // namespace palpctl
