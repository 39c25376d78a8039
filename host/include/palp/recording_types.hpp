// SPDX-License-Identifier: Apache-2.0
// The recording in memory: its columns, one row, the sidecar's metadata and a whole recording,
// in the recording's lab units (s, A, mm, Pa). The analysis takes these (palp::analysis links no
// file, device or robot code); reading and writing the files is recording.hpp's, in the
// recording library (palp::recording). The format itself: docs/recording-format.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace palp {

// --- columns -----------------------------------------------------------------------------------

/// The columns of a recording, in the order the SDK writes them.
enum class Column : std::uint8_t {
  sample_index,  ///< the stream's sample index, from 0 (gaps show as jumps)
  t_s,           ///< device time, s (required)
  i_cmd_A,       ///< commanded coil current, A
  i_A,           ///< measured coil current, A (required)
  z_mm,          ///< coil position, mm, +z into the specimen (required)
  p1_Pa,         ///< pressure channel 1, Pa
  p2_Pa,         ///< pressure channel 2, Pa
  p3_Pa,         ///< pressure channel 3, Pa
  p4_Pa,         ///< pressure channel 4, Pa
  p5_Pa,         ///< pressure channel 5, Pa
  p6_Pa,         ///< pressure channel 6, Pa
  status,        ///< the device's StatusBit bits (0..65535)
  rep,           ///< repetition, from 0 (as the device's ProgramStatus.repetition counts)
};
inline constexpr std::size_t kColumnCount = 13;

/// Header names, indexed by Column.
inline constexpr std::array<std::string_view, kColumnCount> kColumnNames = {
    "sample_index", "t_s",   "i_cmd_A", "i_A",   "z_mm",   "p1_Pa", "p2_Pa",
    "p3_Pa",        "p4_Pa", "p5_Pa",   "p6_Pa", "status", "rep"};

constexpr std::string_view column_name(Column c) {
  return kColumnNames[static_cast<std::size_t>(c)];
}
/// The pressure column of channel 0..5 (p1_Pa..p6_Pa).
constexpr Column pressure_column(std::size_t channel) {
  return static_cast<Column>(static_cast<std::size_t>(Column::p1_Pa) + channel);
}

/// A set of columns. t_s, i_A and z_mm are always in it: a recording cannot be without them.
class ColumnSet {
 public:
  /// Every column: what the SDK writes by default.
  static constexpr ColumnSet all() { return ColumnSet((1u << kColumnCount) - 1u); }
  /// Only t_s, i_A and z_mm.
  static constexpr ColumnSet required() { return ColumnSet(kRequiredBits); }

  constexpr bool has(Column c) const { return (bits_ & bit(c)) != 0; }
  constexpr ColumnSet with(Column c) const { return ColumnSet(bits_ | bit(c)); }
  /// Removing a required column leaves the set unchanged.
  constexpr ColumnSet without(Column c) const { return ColumnSet(bits_ & ~bit(c)); }
  constexpr bool operator==(const ColumnSet&) const = default;

 private:
  static constexpr std::uint16_t bit(Column c) {
    return static_cast<std::uint16_t>(1u << static_cast<unsigned>(c));
  }
  static constexpr std::uint16_t kRequiredBits = static_cast<std::uint16_t>(
      (1u << static_cast<unsigned>(Column::t_s)) | (1u << static_cast<unsigned>(Column::i_A)) |
      (1u << static_cast<unsigned>(Column::z_mm)));
  explicit constexpr ColumnSet(unsigned bits)
      : bits_(static_cast<std::uint16_t>(bits | kRequiredBits)) {}
  std::uint16_t bits_;
};

/// One row of a recording: one sample, in the recording's lab units.
struct RecordingRow {
  std::uint64_t sample_index = 0;
  double t_s = 0;                ///< device time, s (µs / 1e6 gives the shortest text)
  double i_cmd_A = 0;            ///< commanded coil current, A
  double i_A = 0;                ///< measured coil current, A
  double z_mm = 0;               ///< coil position, mm, +z into the specimen
  std::array<double, 6> p_Pa{};  ///< pressure channels 1..6, Pa
  std::uint16_t status = 0;      ///< StatusBit bits
  int rep = 0;                   ///< repetition, from 0
};

// --- the sidecar -------------------------------------------------------------------------------

/// The sidecar's schema name and version, its "schema" key. The reader accepts version 1; keys
/// added later within version 1 land in Sidecar::extra.
inline constexpr std::string_view kRecordingSchema = "palp.recording/1";

/// The JSON sidecar (`run.json` beside `run.csv`): what a recording needs to be understood
/// without its author. Missing values are JSON null with a `<key>_reason`, never NaN.
struct Sidecar {
  std::string sdk_version;  ///< the writing SDK's "major.minor.patch"; the writer fills it in
                            ///< when empty
  std::string created_utc;  ///< "2025-01-31T14:05:09Z"; the writer fills it in when empty
  /// Program parameters, device and firmware info, the calibration in force: JSON objects, or
  /// null when unknown. A null one is written with `<key>_reason` (`program_reason`, ...) taken
  /// from `extra` when it holds one, else "not given to the recording writer".
  nlohmann::json program;
  nlohmann::json device;
  nlohmann::json calibration;
  /// Where the stroke's origin (the home position) is on the z_mm axis; nullopt when unknown,
  /// and then stroke_origin_z_mm_reason says why (the writer puts "not given to the recording
  /// writer" when it is empty).
  std::optional<double> stroke_origin_z_mm;
  std::string stroke_origin_z_mm_reason;
  /// What was zeroed before the measurement (offsets set in the device's RAM), in order: an
  /// array of objects, e.g. {"what": "current_offset", "t_device_s": 1.5, "values": [0.0021],
  /// "values_unit": "A", "committed": false}. Empty when nothing was zeroed.
  nlohmann::json zeroing = nlohmann::json::array();
  /// Every other key, kept as it was: written after the known keys, read back here.
  nlohmann::json extra = nlohmann::json::object();

  /// Filled by the reader from the sidecar (the writer computes its own): the CSV's data rows and
  /// its CRC-32 (zlib's) over every byte, which tie the sidecar to its CSV.
  std::optional<std::uint64_t> csv_rows;
  std::optional<std::uint32_t> csv_crc32;
};

// --- a whole recording -------------------------------------------------------------------------

/// Where the repetition numbers came from.
enum class RepSource : std::uint8_t {
  column,                   ///< the file's rep column (or the caller's rows)
  split_at_current_minima,  ///< the file had none: split_repetitions_at_current_minima(i_A)
};

/// A recording in memory, one vector per column (all the same length). t_s, i_A, z_mm and rep
/// are always there; the other columns are engaged when the file had them. A default-constructed
/// Recording has every column (empty), ready for append().
struct Recording {
  std::vector<double> t_s;   ///< s, never decreasing
  std::vector<double> i_A;   ///< A
  std::vector<double> z_mm;  ///< mm, +z into the specimen
  std::vector<int> rep;      ///< from 0
  RepSource rep_source = RepSource::column;

  std::optional<std::vector<std::uint64_t>> sample_index = std::vector<std::uint64_t>{};
  std::optional<std::vector<double>> i_cmd_A = std::vector<double>{};
  std::array<std::optional<std::vector<double>>, 6> p_Pa = {
      std::vector<double>{}, std::vector<double>{}, std::vector<double>{},
      std::vector<double>{}, std::vector<double>{}, std::vector<double>{}};
  std::optional<std::vector<std::uint16_t>> status = std::vector<std::uint16_t>{};

  /// The sidecar, when there was one (a LabVIEW export has none).
  std::optional<Sidecar> sidecar;
  /// Header names the reader did not know, in file order; their cells are not read.
  std::vector<std::string> ignored_columns;

  std::size_t size() const { return t_s.size(); }
  /// The columns this recording has (rep counts as present: it always is).
  ColumnSet columns() const;
  /// Appends a row to every column the recording has; the row's other fields are dropped.
  void append(const RecordingRow& row);
};

/// Splits a current trace into repetitions at its minima, for a recording without a rep column;
/// returns the repetition (from 0) of every sample. The rule:
///
///   1. lo, hi = the 1st and 99th percentiles of i_A (so a spike cannot move them);
///      range = hi − lo; σ = the noise, median(|Δi_A|) / (0.6745·√2) over neighbouring samples.
///   2. When range ≤ 20·σ (a hold, not a ramp), everything is repetition 0.
///   3. A Schmitt trigger walks the samples: "up" once i_A ≥ lo + range/2 (the current has risen
///      by half its range), "down" once i_A ≤ lo + range/4 (back near the ramp's start). The
///      band between the two levels is thousands of times the noise of a lab ramp, so noise
///      never toggles it.
///   4. Every "down" stretch between two "up" stretches holds one boundary: with m the least
///      i_A in the stretch and tol = max(range/50, 4·σ), the samples within tol of m form the
///      bottom (from its first to its last sample: L samples); the next repetition starts at
///      the middle of the bottom, the first bottom sample + floor(L/2). A symmetric staircase
///      0.5→3→0.5 A therefore splits exactly where the load starts again.
///
/// A recording with n "up" stretches has n repetitions; what comes before the first and after
/// the last belongs to the first and the last.
std::vector<int> split_repetitions_at_current_minima(std::span<const double> i_A);

}  // namespace palp
