// SPDX-License-Identifier: Apache-2.0
// Recordings: streamed probe samples as a CSV with a JSON sidecar of the same name
// (`run.csv` + `run.json`). The format, for people and for other programs, is
// docs/recording-format.md; this header is the SDK's side of it.
//
//   palp::RecordingWriter writer("data/run");             // will become data/run.csv + .json
//   for (const palp::Sample& s : samples)
//     writer.append({.sample_index = s.index, .t_s = s.t_device_s, .i_cmd_A = s.i_cmd_A,
//                    .i_A = s.i_A, .z_mm = s.z_m * 1e3, .p_Pa = s.p_Pa, .status = s.status,
//                    .rep = repetition});
//   writer.finish(sidecar);                               // both files appear now, or neither
//
//   palp::Recording r = palp::read_recording("data/run.csv");
//   for (std::size_t k = 0; k < r.size(); ++k) use(r.t_s[k], r.i_A[k], r.z_mm[k], r.rep[k]);
//
// Units are the recording's lab units, carried in every name (s, A, mm, Pa), not the SDK's SI:
// a recording is read by people and by spreadsheets. z_mm follows DESIGN.md's axis: +z points
// from the probe into the specimen, with any zero (the sidecar's stroke_origin_z_mm says where
// the stroke's origin is, when it is known).
//
// Numbers are written in the shortest form that reads back to the same double (std::to_chars),
// so a recording written and read back is bit-exact, -0.0 included. NaN and infinities are
// never written: the writer refuses them, the reader rejects them.
//
// Every malformed file is a palp::RecordingError that names the file, the 1-based line (0 when
// the problem is not on one line) and the problem. Wrong arguments are palp::ConfigError.
//
// The types (Recording, RecordingRow, Sidecar, columns) are in recording_types.hpp.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "palp/recording_types.hpp"

namespace palp {

// --- the sidecar as JSON ----------------------------------------------------------------------

/// The sidecar as JSON (keys in the order docs/recording-format.md lists them, extra last).
/// Throws ConfigError when a field cannot be written as the schema says (program not an object
/// or null, zeroing not an array, stroke_origin_z_mm not finite, extra naming a known key).
nlohmann::json sidecar_to_json(const Sidecar& sidecar);
/// Reads a sidecar from JSON. Throws RecordingError(file, 0, problem) for a wrong schema, a
/// missing required key or a wrong type (the problem names the key). `file` is only for
/// messages.
Sidecar sidecar_from_json(const nlohmann::json& json, const std::string& file = "sidecar");
/// Reads a sidecar file. Invalid JSON is a RecordingError with the line and column.
Sidecar read_sidecar(const std::filesystem::path& json_path);

/// nlohmann's ADL hooks: `nlohmann::json j = sidecar;`, `j.get<palp::Sidecar>()`.
void to_json(nlohmann::json& json, const Sidecar& sidecar);
void from_json(const nlohmann::json& json, Sidecar& sidecar);

// --- reading -----------------------------------------------------------------------------------

struct ReadOptions {
  /// Read `<stem>.json` beside the CSV when it exists.
  bool read_sidecar = true;
  /// Refuse a sidecar whose csv_rows / csv_crc32 do not match the CSV: the two files are then
  /// not from one write (an interrupted overwrite, or a CSV edited by hand).
  bool check_sidecar_matches_csv = true;
};

/// Reads a recording: the CSV, and its sidecar when there is one.
///
/// The CSV: a header row, then one row per sample. Accepted: comma or tab separators (the
/// header's decides: a tab in it means tab-separated), CRLF or LF line ends, a UTF-8 byte order
/// mark, lines starting with `#` (comments) and blank lines anywhere, spaces around cells, any
/// column order. Required columns: t_s, i_A, z_mm; the other known columns are read when present;
/// unknown columns are listed in ignored_columns and not read. Integer columns accept a whole
/// number written as a decimal ("3.0").
///
/// Rejected, each with the line number and the problem: an empty file; a header without data
/// rows; a missing required column or a repeated one; a row with more or fewer fields than the
/// header (in a comma-separated file a decimal comma shows up this way, and the message says so);
/// an empty cell; a decimal comma; a cell that is not a number (NaN and infinities included); a
/// whole-number column holding a fraction or an out-of-range value; t_s decreasing.
///
/// A line longer than 64 KiB is refused as soon as its first 64 KiB are read (memory stays
/// bounded whatever the file); a message quotes at most 60 bytes of the file, with control and
/// non-ASCII bytes as \xNN (docs/recording-format.md, "Limits").
///
/// Without a rep column, repetitions come from split_repetitions_at_current_minima(i_A).
Recording read_recording(const std::filesystem::path& csv, const ReadOptions& options = {});

/// The 1-based file line of every data row of a recording CSV, as read_recording numbers them
/// (comments, blank lines and the header skipped): how an analysis names the lines of a problem.
/// The same limits and refusals for the file's lines as read_recording.
std::vector<std::size_t> recording_row_lines(const std::filesystem::path& csv);

// --- writing -----------------------------------------------------------------------------------

enum class Overwrite : bool { no, yes };

struct WriterOptions {
  /// The columns to write, in the canonical order (t_s, i_A, z_mm are always written).
  ColumnSet columns = ColumnSet::all();
  /// no: refuse to start (and to finish) when run.csv or run.json already exists.
  Overwrite overwrite = Overwrite::no;
};

/// The CSV a path names: `run.csv` as it is, anything else with `.csv` appended (`run` →
/// `run.csv`, `run.v2` → `run.v2.csv`).
std::filesystem::path recording_csv_path(const std::filesystem::path& csv_or_stem);
/// The sidecar beside a CSV: `run.csv` → `run.json`.
std::filesystem::path recording_sidecar_path(const std::filesystem::path& csv);

/// Writes a recording row by row, atomically.
///
/// Rows go to a hidden temporary file in the destination directory (`.run.csv.tmp-<pid>-<n>`)
/// through a 1 MiB buffer (no flush per row: 10^6 full rows, 150 MB, take about half a second
/// to write and as long to read). finish() writes the sidecar to a temporary file too, flushes
/// both to disk (fsync), then renames the sidecar and then the CSV to their final names. The
/// CSV's rename is the commit point:
///   - a crash before it leaves no run.csv (at most an orphan run.json, which no reader opens
///     without its CSV) and never a CSV without its sidecar, which would pass for a LabVIEW
///     export;
///   - a crash between the renames while overwriting leaves the new run.json beside the old
///     run.csv, and the sidecar's csv_rows / csv_crc32 make read_recording refuse the pair.
/// Temporary files a crash leaves behind (`.*.tmp-*`) can be deleted. An unfinished writer's
/// destructor deletes its temporary files and leaves nothing under the final names.
class RecordingWriter {
 public:
  /// Creates the temporary CSV and writes the header. Throws ConfigError when the recording
  /// exists and options.overwrite is no, RecordingError when the file cannot be created.
  explicit RecordingWriter(const std::filesystem::path& csv_or_stem, WriterOptions options = {});
  ~RecordingWriter();
  RecordingWriter(RecordingWriter&&) noexcept;
  RecordingWriter& operator=(RecordingWriter&&) noexcept;
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  /// Appends a row. Throws ConfigError, writing nothing, for a value that is NaN or infinite or
  /// a t_s below the previous row's (the reader would refuse the file).
  void append(const RecordingRow& row);
  /// Writes the sidecar and makes both files appear under their final names. The writer fills
  /// in sdk_version and created_utc when they are empty, and csv_rows / csv_crc32 always.
  /// Throws ConfigError, with nothing renamed and the writer still usable, when no row was
  /// appended or the sidecar cannot be written (see sidecar_to_json); RecordingError when the
  /// disk refuses. Returns the sidecar as written (those four keys filled in).
  Sidecar finish(const Sidecar& sidecar);

  std::uint64_t rows() const;
  bool finished() const;
  const std::filesystem::path& csv_path() const;      ///< the final name
  const std::filesystem::path& sidecar_path() const;  ///< the final name

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes a whole recording (its columns, and its sidecar or an empty Sidecar with the reasons
/// filled in) with a RecordingWriter. Throws ConfigError when the columns differ in length.
void write_recording(const std::filesystem::path& csv_or_stem, const Recording& recording,
                     Overwrite overwrite = Overwrite::no);

}  // namespace palp
