// SPDX-License-Identifier: Apache-2.0
// The tidy CSV of a map or a result directory (issue 22): one table, one row per point and
// repetition, that pandas.read_csv(f) or MATLAB readtable(f) read in one line. The columns, units
// and rules are docs/result-format.md "The tidy CSV"; `palpctl export --format csv` writes it.
//
//   palp::TidyCsvExport e = palp::export_tidy_csv("results/pad-map", "pad-map.csv");
//   for (const std::string& d : e.damaged) std::cerr << d << "\n";   // their rows say why too
//
// The rows: every grid point of a map (row-major; row and column 1-based), one row per repetition
// of its indentation (rep as the recording numbers it, from 0), each repetition analysed alone
// with the result's own analysis parameters (as result.json's `_sd` are computed: analyze_run),
// its keys those of result.json's "analysis" in lab units. A point without repetitions (not
// mapped, not indented, not analysable, or damaged) gets one row with rep empty and the reason in
// point_reason. A single result directory gives its repetitions with row and column empty.
//
// A damaged point (its result directory cannot be read or analysed again) does not stop the
// export: its row carries the reader's error in point_reason, and TidyCsvExport::damaged names it.
// Everything else that is wrong stops it with an error and writes nothing: INPUT neither a map
// nor a result directory (ConfigError), a malformed map.json (ConfigError from load_map), an
// output that may not be replaced (ConfigError), a file that cannot be written (RecordingError).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "palp/analysis/indentation.hpp"
#include "palp/recording.hpp"

namespace palp {

/// How every tidy CSV's header line begins (the columns that say where a row belongs). An
/// existing file is replaced (Overwrite::yes) only when its first line begins so.
inline constexpr std::string_view kTidyCsvHeadColumns = "row,column,rep,x_mm,y_mm,z_mm,point_reason";

/// What an export wrote.
struct TidyCsvExport {
  std::size_t rows = 0;                ///< data rows (the header not counted)
  std::size_t points = 0;              ///< grid points (1 for a result directory)
  std::vector<std::string> damaged;    ///< "the reader's error" per damaged point, in row order
};

/// The column names, in order, for results analysed with `params` (its tangent depths give the
/// k_at_depth_<d>_mm_N_per_mm columns).
std::vector<std::string> tidy_csv_columns(const analysis::IndentationParams& params);

/// The tidy CSV of `input` (a map directory, with map.json, or a result directory, with
/// result.json) as text; `summary` (if given) says what it holds.
std::string tidy_csv(const std::filesystem::path& input, TidyCsvExport* summary = nullptr);

/// Whether `file` may be written with `overwrite`: absent; or, with Overwrite::yes, a regular file
/// whose first line begins with kTidyCsvHeadColumns (palp wrote it). Else ConfigError naming it.
void check_tidy_csv_replaceable(const std::filesystem::path& file, Overwrite overwrite);

/// tidy_csv(input) written to `file` atomically (a hidden temporary sibling, flushed, renamed
/// into place; its parent directory created): a reader sees the whole table or the old file.
/// check_tidy_csv_replaceable runs before the analysis and again before the rename.
TidyCsvExport export_tidy_csv(const std::filesystem::path& input, const std::filesystem::path& file,
                              Overwrite overwrite = Overwrite::no);

}  // namespace palp
