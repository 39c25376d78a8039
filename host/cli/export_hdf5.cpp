// SPDX-License-Identifier: Apache-2.0
// palpctl export --format hdf5 (export_hdf5.hpp).
#include "export_hdf5.hpp"

#include <filesystem>
#include <iostream>

#include "palp/error.hpp"
#ifdef PALP_HAVE_HDF5
#include "palp/hdf5.hpp"
#endif
#include "palp/recording.hpp"
#include "palp/result.hpp"

namespace palpctl {

namespace fs = std::filesystem;

#ifdef PALP_HAVE_HDF5
bool hdf5_available() { return true; }

namespace {

std::size_t samples_of(const palp::LoadedResult& r) {
  std::size_t rows = 0;
  for (const auto& rec : r.recordings) rows += rec.second.size();
  return rows;
}

/// A map directory: every point's result; a damaged point is named on stderr and kept in the
/// file as lost, the others are written.
json export_map(const std::string& input, const std::string& out, palp::Overwrite mode, std::string& text) {
  const palp::LoadedMap m = palp::load_map_results(input);
  palp::write_map_hdf5(out, m, mode);
  for (const auto& [dir, why] : m.damaged)
    std::cerr << "palpctl: export: a damaged point (the file says so in its group; the export went on): " << why
              << "\n";
  std::size_t rows = 0;
  for (const auto& r : m.results) rows += samples_of(r.second);
  json damaged = json::array();
  for (const auto& d : m.damaged) damaged.push_back(d.first);
  const std::size_t grid = static_cast<std::size_t>(m.map.rows) * static_cast<std::size_t>(m.map.columns);
  text = "a map of " + std::to_string(m.map.points.size()) + " of " + std::to_string(grid) + " points (" +
         std::to_string(m.results.size()) + " with results" +
         (m.damaged.empty() ? "" : ", " + std::to_string(m.damaged.size()) + " damaged") + "), " +
         std::to_string(rows) + " samples" + (m.map.complete ? "" : "; the map is not complete");
  return {{"content", "map"},       {"rows", rows},         {"points", m.map.points.size()},
          {"grid_points", grid},    {"complete", m.map.complete}, {"results", m.results.size()},
          {"damaged", damaged}};
}

}  // namespace

int export_hdf5(const Context& ctx, const std::string& input, const std::string& out, bool overwrite) {
  const auto mode = overwrite ? palp::Overwrite::yes : palp::Overwrite::no;
  std::error_code ec;
  if (!overwrite && fs::exists(fs::symlink_status(out, ec)))  // before reading a whole map
    throw palp::ConfigError(out + " already exists; choose another --out, or pass --overwrite to replace it");
  if (!fs::is_directory(input, ec) && palp::is_hdf5_file(input) && palp::hdf5_content(input) != palp::kHdf5ContentRecording)
    throw palp::ConfigError(input + " is already a palp HDF5 file (a " + palp::hdf5_content(input) +
                            "); export reads a map or result directory, or a recording");
  if (const fs::path parent = fs::path(out).parent_path(); !parent.empty())
    fs::create_directories(parent);  // as the tidy CSV's export does
  json summary;
  std::string text;
  if (fs::is_directory(input, ec) && fs::exists(fs::path(input) / "map.json", ec)) {
    summary = export_map(input, out, mode, text);
  } else if (fs::is_directory(input, ec)) {
    if (!fs::exists(fs::path(input) / std::string(palp::kResultFile), ec))
      throw palp::ConfigError(input + " is neither a map (no map.json) nor a result directory (no result.json)");
    palp::LoadedResult r = palp::load_result(input);
    const std::size_t rows = samples_of(r);
    if (r.experiment == "identification") {
      const palp::LoadedIdentification id = palp::identification_of(std::move(r));
      palp::write_identification_hdf5(out, id, mode);
      const std::size_t lines = id.frf ? id.frf->lines.size() : 0;
      summary = {{"content", "identification"}, {"rows", rows}, {"frf_lines", lines}};
      text = "an identification of " + std::to_string(rows) + " samples and " +
             (id.frf ? std::to_string(lines) + " response lines" : std::string("no response (not analysed)"));
    } else {
      palp::write_result_hdf5(out, r, mode);
      summary = {{"content", "result"}, {"rows", rows}};
      text = "a result of " + std::to_string(rows) + " samples";
    }
  } else {
    const palp::Recording r =
        palp::is_hdf5_file(input) ? palp::read_recording_hdf5(input) : palp::read_recording(input);
    palp::write_recording_hdf5(out, r, mode);
    summary = {{"content", "recording"}, {"rows", r.size()}};
    text = "a recording of " + std::to_string(r.size()) + " samples";
  }
  if (ctx.json) {
    summary["file"] = out;
    summary["format"] = "hdf5";
    print_json(summary);
  } else {
    std::cout << "wrote " << out << ": " << text << " (HDF5, docs/hdf5-format.md)\n";
  }
  return kOk;
}
#else
bool hdf5_available() { return false; }

int export_hdf5(const Context&, const std::string&, const std::string&, bool) {
  throw palp::ConfigError("--format hdf5: this palpctl was built without HDF5 (install libhdf5-dev, "
                          "scripts/install-deps, and build again); use --format csv");
}
#endif

}  // namespace palpctl
