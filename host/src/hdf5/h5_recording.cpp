// SPDX-License-Identifier: Apache-2.0
// A recording as an HDF5 group (docs/hdf5-format.md "A recording's group"), and the recording
// file of palp/hdf5.hpp.
#include "hdf5/h5_recording.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include <nlohmann/json.hpp>

#include "format/text_input.hpp"
#include "palp/error.hpp"
#include "palp/hdf5.hpp"
#include "palp/probe.hpp"
#include "recording/internal.hpp"

namespace palp::hdf5_detail {

namespace fs = std::filesystem;
namespace rd = recording_detail;
using nlohmann::json;

namespace {

/// Each column's `unit` attribute, indexed by Column: the lab units of docs/recording-format.md,
/// "1" for the index, the status bits and the repetition (dimensionless).
constexpr std::array<std::string_view, kColumnCount> kColumnUnits = {
    "1", "s", "A", "A", "mm", "Pa", "Pa", "Pa", "Pa", "Pa", "Pa", "1", "1"};

constexpr std::string_view name_of(Column c) { return column_name(c); }
std::string unit_of(Column c) { return std::string(kColumnUnits[static_cast<std::size_t>(c)]); }

constexpr std::string_view kRepSourceColumn = "column";
constexpr std::string_view kRepSourceSplit = "split_at_current_minima";

void refuse_non_finite(const std::vector<double>& v, std::string_view column, const Where& w) {
  for (std::size_t k = 0; k < v.size(); ++k)
    if (!std::isfinite(v[k]))
      throw ConfigError(w.file + ": column " + std::string(column) + " row " + std::to_string(k) +
                        " is not a finite number; a recording holds none");
}

}  // namespace

void write_recording_group(hid_t parent, const Where& w, const Recording& r) {
  rd::check_column_lengths(r, "write_recording_hdf5");
  if (r.size() == 0) throw ConfigError(w.file + ": the recording has no samples");
  refuse_non_finite(r.t_s, "t_s", w);
  refuse_non_finite(r.i_A, "i_A", w);
  refuse_non_finite(r.z_mm, "z_mm", w);
  if (r.i_cmd_A) refuse_non_finite(*r.i_cmd_A, "i_cmd_A", w);
  for (std::size_t k = 0; k < r.p_Pa.size(); ++k)
    if (r.p_Pa[k]) refuse_non_finite(*r.p_Pa[k], name_of(pressure_column(k)), w);
  nlohmann::ordered_json side;
  if (r.sidecar) {
    Sidecar s = *r.sidecar;  // completed as RecordingWriter completes it
    if (s.sdk_version.empty()) s.sdk_version = sdk_version();
    if (s.created_utc.empty()) s.created_utc = rd::utc_now();
    side = rd::sidecar_document(s);  // ConfigError before anything is written
  }

  const Id g = create_group(parent, w);
  const auto column = [&](Column c, const auto& values) {
    using T = typename std::decay_t<decltype(values)>::value_type;
    put_column<T>(g.get(), std::string(name_of(c)).c_str(), std::span<const T>(values), unit_of(c), w);
  };
  if (r.sample_index) column(Column::sample_index, *r.sample_index);
  column(Column::t_s, r.t_s);
  if (r.i_cmd_A) column(Column::i_cmd_A, *r.i_cmd_A);
  column(Column::i_A, r.i_A);
  column(Column::z_mm, r.z_mm);
  for (std::size_t k = 0; k < r.p_Pa.size(); ++k)
    if (r.p_Pa[k]) column(pressure_column(k), *r.p_Pa[k]);
  if (r.status) column(Column::status, *r.status);
  column(Column::rep, r.rep);

  put_attr(g.get(), "rows", static_cast<std::uint64_t>(r.size()), w);
  put_attr(g.get(), "rep_source",
           r.rep_source == RepSource::column ? kRepSourceColumn : kRepSourceSplit, w);
  put_attr(g.get(), "ignored_columns", json(r.ignored_columns).dump(), w);
  if (r.sidecar) {
    put_attr(g.get(), "sidecar", side.dump(), w);
    // copies for a quick look (h5py, HDFView), never read back: the reader reads `sidecar`
    put_json_scalars(g.get(), "", json(side), {"program", "device", "calibration"}, w);
  }
}

Recording read_recording_group(hid_t parent, const char* name, const Where& w_parent,
                               const fs::path& file) {
  const Id g = open_group(parent, name, w_parent);
  const Where w = w_parent.at(name);
  Recording r;
  const auto doubles = [&](Column c) {
    const std::uint64_t limit = max_rows(file, sizeof(double));
    return get_column<double>(g.get(), std::string(name_of(c)).c_str(), limit, w);
  };
  const auto present = [&](Column c) { return has_link(g.get(), std::string(name_of(c)).c_str()); };
  r.t_s = doubles(Column::t_s);
  r.i_A = doubles(Column::i_A);
  r.z_mm = doubles(Column::z_mm);
  r.rep = get_column<int>(g.get(), "rep", max_rows(file, sizeof(int)), w);
  r.sample_index.reset();
  if (present(Column::sample_index))
    r.sample_index = get_column<std::uint64_t>(g.get(), "sample_index", max_rows(file, 8), w);
  r.i_cmd_A.reset();
  if (present(Column::i_cmd_A)) r.i_cmd_A = doubles(Column::i_cmd_A);
  for (std::size_t k = 0; k < r.p_Pa.size(); ++k) {
    r.p_Pa[k].reset();
    if (present(pressure_column(k))) r.p_Pa[k] = doubles(pressure_column(k));
  }
  r.status.reset();
  if (present(Column::status))
    r.status = get_column<std::uint16_t>(g.get(), "status", max_rows(file, 2), w);

  try {
    rd::check_column_lengths(r, "columns of unequal length");
  } catch (const ConfigError& e) {
    fail(w, e.what());
  }
  if (r.size() == 0) fail(w, "the recording has no samples");
  const auto finite = [&](const std::vector<double>& v, Column c) {
    for (std::size_t k = 0; k < v.size(); ++k)
      if (!std::isfinite(v[k])) fail(w.at(name_of(c)), "row " + std::to_string(k) + " is not a finite number");
  };
  finite(r.t_s, Column::t_s);
  finite(r.i_A, Column::i_A);
  finite(r.z_mm, Column::z_mm);
  if (r.i_cmd_A) finite(*r.i_cmd_A, Column::i_cmd_A);
  for (std::size_t k = 0; k < r.p_Pa.size(); ++k)
    if (r.p_Pa[k]) finite(*r.p_Pa[k], pressure_column(k));
  for (std::size_t k = 1; k < r.t_s.size(); ++k)
    if (r.t_s[k] < r.t_s[k - 1])
      fail(w.at("t_s"), "decreases at row " + std::to_string(k) + "; it must not decrease");

  const std::string source = get_string_attr(g.get(), "rep_source", w, 256);
  if (source == kRepSourceColumn) r.rep_source = RepSource::column;
  else if (source == kRepSourceSplit) r.rep_source = RepSource::split_at_current_minima;
  else fail(w.at("rep_source"), "is " + format::quoted(source) + ", not \"column\" or \"split_at_current_minima\"");

  const json ignored = json::parse(get_string_attr(g.get(), "ignored_columns", w), nullptr, false);
  if (!ignored.is_array() || !std::all_of(ignored.begin(), ignored.end(), [](const json& e) { return e.is_string(); }))
    fail(w.at("ignored_columns"), "is not a JSON array of strings");
  r.ignored_columns = ignored.get<std::vector<std::string>>();

  if (has_attr(g.get(), "sidecar")) {
    const json doc = json::parse(get_string_attr(g.get(), "sidecar", w), nullptr, false);
    if (doc.is_discarded()) fail(w.at("sidecar"), "is not valid JSON");
    r.sidecar = sidecar_from_json(doc, w.file + " " + w.object + "/sidecar");
  }
  return r;
}

}  // namespace palp::hdf5_detail

namespace palp {

namespace fs = std::filesystem;

void write_recording_hdf5(const fs::path& path, const Recording& recording, Overwrite overwrite) {
  using namespace hdf5_detail;
  write_palp_file(path, overwrite, kHdf5ContentRecording, [&](hid_t root) {
    write_recording_group(root, Where{path.string(), "/recording"}, recording);
  });
}

Recording read_recording_hdf5(const fs::path& path) {
  using namespace hdf5_detail;
  const Id f = open_palp_file(path, kHdf5ContentRecording);
  return read_recording_group(f.get(), "recording", Where{path.string(), "/"}, path);
}

std::string hdf5_content(const fs::path& path) {
  std::string content;
  (void)hdf5_detail::open_palp_file(path, "", &content);
  return content;
}

}  // namespace palp
