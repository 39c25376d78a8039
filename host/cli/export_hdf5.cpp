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

int export_hdf5(const Context& ctx, const std::string& input, const std::string& out, bool overwrite) {
  const auto mode = overwrite ? palp::Overwrite::yes : palp::Overwrite::no;
  std::error_code ec;
  std::string content;
  std::size_t rows = 0;
  if (fs::is_directory(input, ec)) {
    if (fs::exists(fs::path(input) / "map.json", ec))
      throw palp::ConfigError(input + " is a map; a map as one HDF5 file is not written yet (issue 22): export its "
                                      "points' result directories one by one, or use --format csv");
    if (!fs::exists(fs::path(input) / std::string(palp::kResultFile), ec))
      throw palp::ConfigError(input + " is neither a recording nor a result directory (no result.json)");
    const palp::LoadedResult r = palp::load_result(input);
    palp::write_result_hdf5(out, r, mode);
    content = "result";
    for (const auto& rec : r.recordings) rows += rec.second.size();
  } else {
    const palp::Recording r =
        palp::is_hdf5_file(input) ? palp::read_recording_hdf5(input) : palp::read_recording(input);
    palp::write_recording_hdf5(out, r, mode);
    content = "recording";
    rows = r.size();
  }
  if (ctx.json)
    print_json({{"file", out}, {"format", "hdf5"}, {"content", content}, {"rows", rows}});
  else
    std::cout << "wrote " << out << ": a " << content << " of " << rows << " sample" << (rows == 1 ? "" : "s")
              << " (HDF5, docs/hdf5-format.md)\n";
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
