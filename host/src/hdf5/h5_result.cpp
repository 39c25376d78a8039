// A result directory as one HDF5 file (docs/hdf5-format.md "A result file"): result.json as
// text and its analysed numbers as typed attributes, every recording as a group.
#include <string>

#include <nlohmann/json.hpp>

#include "hdf5/h5.hpp"
#include "hdf5/h5_recording.hpp"
#include "palp/error.hpp"
#include "palp/hdf5.hpp"

namespace palp {

namespace fs = std::filesystem;
using nlohmann::json;

void write_result_hdf5(const fs::path& path, const LoadedResult& result, Overwrite overwrite) {
  using namespace hdf5_detail;
  const json& summary = result.summary;
  if (!summary.is_object() || !summary.contains("recordings") || !summary["recordings"].is_array())
    throw ConfigError(path.string() + ": the result's summary has no \"recordings\" list");
  write_palp_file(path, overwrite, kHdf5ContentResult, [&](hid_t root) {
    const Where wr{path.string(), "/result"};
    const Id g = create_group(root, wr);
    put_attr(g.get(), "result_json", summary.dump(), wr);
    // typed copies for a quick look, never read back: the top-level strings and numbers
    put_json_scalars(g.get(), "", summary, {}, wr);
    for (const char* part : {"analysis", "pressure"}) {
      const json* v = summary.contains(part) ? &summary[part] : nullptr;
      if (v == nullptr || !v->is_object()) continue;
      const Id a = create_group(g.get(), wr.at(part));
      put_json_scalars(a.get(), "", *v, {"k_at_depth_N_per_mm"}, wr.at(part));
    }
    const Where wrec = wr.at("recordings");
    const Id recs = create_group(g.get(), wrec);
    for (const auto& [name, recording] : result.recordings)
      write_recording_group(recs.get(), wrec.at(name), recording);
  });
}

LoadedResult read_result_hdf5(const fs::path& path) {
  using namespace hdf5_detail;
  const Id f = open_palp_file(path, kHdf5ContentResult);
  const Where root{path.string(), "/"};
  const Id g = open_group(f.get(), "result", root);
  const Where wr = root.at("result");
  LoadedResult out;
  out.dir = path;
  out.summary = json::parse(get_string_attr(g.get(), "result_json", wr), nullptr, false);
  if (out.summary.is_discarded() || !out.summary.is_object())
    fail(wr.at("result_json"), "is not a JSON object");
  const json& schema = out.summary.contains("schema") ? out.summary["schema"] : json();
  if (!schema.is_string() || schema.get<std::string>() != kResultSchema)
    fail(wr.at("result_json"), "its schema is not \"" + std::string(kResultSchema) + "\"");
  if (!out.summary.contains("experiment") || !out.summary["experiment"].is_string())
    fail(wr.at("result_json"), "missing key \"experiment\"");
  out.experiment = out.summary["experiment"].get<std::string>();
  const json& names = out.summary.contains("recordings") ? out.summary["recordings"] : json();
  if (!names.is_array()) fail(wr.at("result_json"), "missing key \"recordings\"");
  const Id recs = open_group(g.get(), "recordings", wr);
  for (const json& n : names) {
    if (!n.is_string()) fail(wr.at("result_json"), "\"recordings\" holds a value that is not a name");
    const std::string name = n.get<std::string>();
    out.recordings.emplace_back(name, read_recording_group(recs.get(), name.c_str(), wr.at("recordings"), path));
  }
  return out;
}

}  // namespace palp
