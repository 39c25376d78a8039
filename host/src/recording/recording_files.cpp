// SPDX-License-Identifier: Apache-2.0
// The recording files: their names beside each other, and write_recording() (recording.hpp).
#include "palp/recording.hpp"

#include "palp/error.hpp"
#include "recording/internal.hpp"

namespace palp {
namespace fs = std::filesystem;
namespace rd = recording_detail;

fs::path recording_csv_path(const fs::path& csv_or_stem) {
  if (csv_or_stem.extension() == ".csv") return csv_or_stem;
  fs::path p = csv_or_stem;
  p += ".csv";
  return p;
}

fs::path recording_sidecar_path(const fs::path& csv) {
  fs::path p = csv;
  p.replace_extension(".json");
  return p;
}

void rd::check_column_lengths(const Recording& r, std::string_view who) {
  const std::size_t n = r.size();
  const auto check = [&](std::string_view name, std::size_t size) {
    if (size != n)
      throw ConfigError(std::string(who) + ": column " + std::string(name) + " has " +
                        std::to_string(size) + " values where t_s has " + std::to_string(n));
  };
  check("i_A", r.i_A.size());
  check("z_mm", r.z_mm.size());
  check("rep", r.rep.size());
  if (r.sample_index) check("sample_index", r.sample_index->size());
  if (r.i_cmd_A) check("i_cmd_A", r.i_cmd_A->size());
  for (std::size_t k = 0; k < r.p_Pa.size(); ++k)
    if (r.p_Pa[k]) check(column_name(pressure_column(k)), r.p_Pa[k]->size());
  if (r.status) check("status", r.status->size());
}

void write_recording(const fs::path& csv_or_stem, const Recording& r, Overwrite overwrite) {
  const std::size_t n = r.size();
  rd::check_column_lengths(r, "write_recording");

  RecordingWriter writer(csv_or_stem, {.columns = r.columns(), .overwrite = overwrite});
  RecordingRow row;
  for (std::size_t i = 0; i < n; ++i) {
    row.t_s = r.t_s[i];
    row.i_A = r.i_A[i];
    row.z_mm = r.z_mm[i];
    row.rep = r.rep[i];
    if (r.sample_index) row.sample_index = (*r.sample_index)[i];
    if (r.i_cmd_A) row.i_cmd_A = (*r.i_cmd_A)[i];
    for (std::size_t k = 0; k < r.p_Pa.size(); ++k)
      if (r.p_Pa[k]) row.p_Pa[k] = (*r.p_Pa[k])[i];
    if (r.status) row.status = (*r.status)[i];
    writer.append(row);
  }
  writer.finish(r.sidecar.value_or(Sidecar{}));
}

}  // namespace palp
