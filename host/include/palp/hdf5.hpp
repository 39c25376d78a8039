// SPDX-License-Identifier: Apache-2.0
// Recordings, result directories, maps and identifications as HDF5 files (issue 22): one
// self-describing binary file a lab opens in Python (h5py), MATLAB (h5read) or HDFView without
// palp. The layout, for people and other programs, is docs/hdf5-format.md; this header is the
// SDK's side of it.
//
//   palp::write_recording_hdf5("run.h5", palp::read_recording("run.csv"));
//   palp::Recording r = palp::read_recording_hdf5("run.h5");     // the same Recording again
//
//   palp::write_result_hdf5("solid-p3.h5", palp::load_result("results/solid-p3"));
//   palp::LoadedResult res = palp::read_result_hdf5("solid-p3.h5");
//   palp::IndentationRun again = palp::indentation_run_of(res);  // re-analysable, as from the dir
//
//   palp::write_map_hdf5("pad-map.h5", palp::load_map_results("results/pad-map"));
//   palp::LoadedMap m = palp::read_map_hdf5("pad-map.h5");       // map.json and every point's result
//
//   palp::write_identification_hdf5("sweep.h5", palp::identification_of(palp::load_result("results/sweep")));
//
// The samples are typed columns (float64, uint64, uint16, int32), chunked and deflate-compressed,
// each with a `unit` attribute in the recording's lab units (s, A, mm, Pa; "1" for indices,
// counts and bits). The sidecar is an attribute of the recording's group, as JSON text (so it
// reads back exactly), and its values are also typed attributes for a quick look. Strings are
// fixed-length UTF-8 (HDF5 1.10 crashes on damaged variable-length ones). Values are
// stored as the doubles they are: reading back is bit-exact.
//
// Library palp::hdf5 (palp_hdf5), built only when CMake finds the HDF5 C library (Debian's
// libhdf5-dev); palp::analysis and palp::device never need it.
//
// Writing is atomic, as for every palp file: a hidden temporary file beside the target
// (`.run.h5.tmp-<pid>-<n>`), flushed to disk, renamed into place. An existing target is refused
// with Overwrite::no, and with Overwrite::yes replaced only when palp wrote it (an HDF5 file whose
// root carries palp_format); anything else is a ConfigError and stays untouched.
//
// Reading: a file that is not HDF5, not palp's, of another palp_format version, or damaged (a
// missing or mistyped dataset or attribute, columns of unequal length, more rows than the file
// can hold) is a RecordingError naming the file and the object: one line, never a crash and never
// HDF5's own error stack on stderr.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include <optional>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "palp/analysis/frf.hpp"
#include "palp/map.hpp"
#include "palp/recording.hpp"
#include "palp/result.hpp"

namespace palp {

/// The root attribute `palp_format` of every HDF5 file palp writes. The reader accepts version 1.
inline constexpr std::string_view kHdf5Format = "palp.hdf5/1";

/// What a palp HDF5 file holds: its root attribute `content`.
inline constexpr std::string_view kHdf5ContentRecording = "recording";
inline constexpr std::string_view kHdf5ContentResult = "result";
inline constexpr std::string_view kHdf5ContentMap = "map";
inline constexpr std::string_view kHdf5ContentIdentification = "identification";

/// Whether a file starts with HDF5's signature (\x89HDF\r\n\x1a\n): how palpctl tells an .h5 input
/// from a CSV. False for a file that cannot be read.
bool is_hdf5_file(const std::filesystem::path& path);

/// Writes a recording (its columns and, when it has one, its sidecar) as `path`. ConfigError for
/// columns of unequal length, a recording without samples, or an existing `path` that may not be
/// replaced (above); RecordingError when the disk refuses.
void write_recording_hdf5(const std::filesystem::path& path, const Recording& recording,
                          Overwrite overwrite = Overwrite::no);

/// Reads a recording palp wrote with write_recording_hdf5: the same columns, sidecar, rep_source
/// and ignored_columns. RecordingError (file, 0, problem) for anything else.
Recording read_recording_hdf5(const std::filesystem::path& path);

/// Writes a result directory read back with load_result (result.json and its recordings) as one
/// file: result.json as text and its analysed numbers as attributes, every recording as a group.
void write_result_hdf5(const std::filesystem::path& path, const LoadedResult& result,
                       Overwrite overwrite = Overwrite::no);

/// Reads a result written by write_result_hdf5: `dir` is the file's path, `summary` result.json,
/// `recordings` by their names in the result directory ("indentation.csv").
LoadedResult read_result_hdf5(const std::filesystem::path& path);

// --- maps ---------------------------------------------------------------------------------------

/// A map directory (map.hpp) read whole: map.json and the result directory of every point that
/// has one.
struct LoadedMap {
  std::filesystem::path dir;          ///< the map's directory, or the HDF5 file it was read from
  nlohmann::json document;            ///< map.json as written (its numbers exactly)
  StiffnessMap map;                   ///< map.json read (map_from_json(document))
  /// Each point's result by its MapPoint::result_dir ("points/r1_c1"), in map.json's order.
  std::vector<std::pair<std::string, LoadedResult>> results;
  /// The indented points whose result could not be read: (result_dir, the reader's error). They
  /// stay in `map` with their numbers from map.json; their samples are lost.
  std::vector<std::pair<std::string, std::string>> damaged;
};

/// load_map(dir) and load_result of every indented point's directory. A point whose directory is
/// missing or damaged is listed in `damaged` and the others are read (as the tidy CSV does); a
/// missing or malformed map.json is a ConfigError.
LoadedMap load_map_results(const std::filesystem::path& dir);

/// Writes a map as one file: map.json as text (`document`, which is what is written and read:
/// map_to_json(map) only when `document` is not an object), its plan, settings and analysis (analyze_map: the
/// k_fd grid, line means, the soft and stiff lines) typed, and a group per point holding its
/// result (write_result_hdf5's group, with its repetitions) or why it has none.
void write_map_hdf5(const std::filesystem::path& path, const LoadedMap& map,
                    Overwrite overwrite = Overwrite::no);

/// Reads a map written by write_map_hdf5: the same `document`, `map`, `results` and `damaged`
/// (`dir` is the file). RecordingError naming the file and the object for anything else.
LoadedMap read_map_hdf5(const std::filesystem::path& path);

// --- identifications (sweep, free air) -----------------------------------------------------------

/// An identification result directory (identification_result.hpp): result.json with sweep.csv,
/// and the measured response frf.csv when the run was analysed.
struct LoadedIdentification {
  LoadedResult result;
  std::optional<analysis::Frf> frf;   ///< as analysis::read_frf_table gives frf.csv
};

/// The identification a loaded result directory holds: reads `result.dir`/frf.csv when it is
/// there. ConfigError when the result is not an identification; RecordingError for a bad frf.csv.
LoadedIdentification identification_of(LoadedResult result);

/// Writes an identification as one file: the result's group (as write_result_hdf5) and the
/// response as typed columns (f_Hz, re/im/sigma_m_per_N). ConfigError for another experiment.
void write_identification_hdf5(const std::filesystem::path& path, const LoadedIdentification& id,
                               Overwrite overwrite = Overwrite::no);

/// Reads an identification written by write_identification_hdf5 (`result.dir` is the file).
LoadedIdentification read_identification_hdf5(const std::filesystem::path& path);

/// The root `content` of a palp HDF5 file ("recording", "result", "map" or "identification");
/// RecordingError when the file is not a palp HDF5 file of a version this SDK reads.
std::string hdf5_content(const std::filesystem::path& path);

}  // namespace palp
