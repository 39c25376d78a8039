// SPDX-License-Identifier: Apache-2.0
// A result directory as an HDF5 group and as one file (docs/hdf5-format.md "A result file"):
// result.json as text and its analysed numbers as typed attributes, every recording as a group,
// the repetitions of an indentation as groups.
#include "hdf5/h5_result.hpp"

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "palp/error.hpp"
#include "palp/hdf5.hpp"
#include "hdf5/h5_recording.hpp"

namespace palp::hdf5_detail {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// The repetitions of an indentation result (docs/hdf5-format.md "Repetitions"): `rep<k>` per run
/// of equal `rep` in its recording, in order, with its rows and, when the result re-analyses (as
/// the tidy CSV's rows do: each repetition alone, with the result's own parameters), its numbers.
void write_repetitions(hid_t parent, const Where& w_parent, const LoadedResult& result) {
  if (result.experiment != "indentation" || result.recordings.empty()) return;
  const Where w = w_parent.at("repetitions");
  const Id g = create_group(parent, w);
  const Recording& rec = result.recordings.front().second;
  put_attr(g.get(), "recording", std::string_view(result.recordings.front().first), w);
  std::vector<std::size_t> starts;
  for (std::size_t k = 0; k < rec.rep.size(); ++k)
    if (k == 0 || rec.rep[k] != rec.rep[k - 1]) starts.push_back(k);
  std::vector<json> numbers;
  try {
    const IndentationRun run = indentation_run_of(result);
    if (run.repetitions)
      for (const auto& one : run.repetitions->per_rep)
        numbers.push_back(indentation_summary_json(one, nullptr, run.settings.analysis));
    else
      put_attr(g.get(), "analysis_reason", run.analysis_reason.empty() ? "not analysed" : run.analysis_reason, w);
  } catch (const Error& e) {  // the numbers are a convenience: the samples are written all the same
    put_attr(g.get(), "analysis_reason", std::string_view(e.what()), w);
  }
  for (std::size_t k = 0; k < starts.size(); ++k) {
    const Where wk = w.at("rep" + std::to_string(k));
    const Id r = create_group(g.get(), wk);
    const std::size_t end = k + 1 < starts.size() ? starts[k + 1] : rec.rep.size();
    put_attr(r.get(), "rep", static_cast<std::int64_t>(rec.rep[starts[k]]), wk);
    put_attr(r.get(), "first_row", static_cast<std::uint64_t>(starts[k]), wk);
    put_attr(r.get(), "rows", static_cast<std::uint64_t>(end - starts[k]), wk);
    if (k < numbers.size()) put_json_scalars(r.get(), "", numbers[k], {"k_at_depth_N_per_mm"}, wk);
  }
}

}  // namespace

void write_result_group(hid_t parent, const Where& wr, const LoadedResult& result) {
  const json& summary = result.summary;
  if (!summary.is_object() || !summary.contains("recordings") || !summary["recordings"].is_array())
    throw ConfigError(wr.file + ": the result's summary has no \"recordings\" list");
  const Id g = create_group(parent, wr);
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
  write_repetitions(g.get(), wr, result);
}

LoadedResult read_result_group(hid_t parent, const char* name, const Where& w_parent, const fs::path& file) {
  const Id g = open_group(parent, name, w_parent);
  const Where wr = w_parent.at(name);
  LoadedResult out;
  out.dir = file;
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
    const std::string rec_name = n.get<std::string>();
    out.recordings.emplace_back(rec_name,
                                read_recording_group(recs.get(), rec_name.c_str(), wr.at("recordings"), file));
  }
  return out;
}

}  // namespace palp::hdf5_detail

namespace palp {

void write_result_hdf5(const std::filesystem::path& path, const LoadedResult& result, Overwrite overwrite) {
  using namespace hdf5_detail;
  write_palp_file(path, overwrite, kHdf5ContentResult,
                  [&](hid_t root) { write_result_group(root, Where{path.string(), "/result"}, result); });
}

LoadedResult read_result_hdf5(const std::filesystem::path& path) {
  using namespace hdf5_detail;
  const Id f = open_palp_file(path, kHdf5ContentResult);
  return read_result_group(f.get(), "result", Where{path.string(), "/"}, path);
}

}  // namespace palp
