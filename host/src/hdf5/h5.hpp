// SPDX-License-Identifier: Apache-2.0
// The HDF5 C API behind palp/hdf5.hpp (not installed): handles that close themselves, typed
// attributes and columns, and palp's atomic file. Every failure is an exception naming the file
// and the object (RecordingError), never HDF5's error stack on stderr.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "palp/recording.hpp"

namespace palp::hdf5_detail {

/// An HDF5 identifier and the call that releases it.
class Id {
 public:
  Id() = default;
  Id(hid_t id, herr_t (*closer)(hid_t)) : id_(id), close_(closer) {}
  ~Id() { reset(); }
  Id(Id&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = H5I_INVALID_HID; }
  Id& operator=(Id&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = o.id_;
      close_ = o.close_;
      o.id_ = H5I_INVALID_HID;
    }
    return *this;
  }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Gives the identifier up without closing it.
  hid_t release() {
    const hid_t id = id_;
    id_ = H5I_INVALID_HID;
    return id;
  }
  void reset() {
    if (id_ >= 0 && close_ != nullptr) close_(id_);
    id_ = H5I_INVALID_HID;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  herr_t (*close_)(hid_t) = nullptr;
};

/// Where an object is, for messages: the file and the object's path inside it.
struct Where {
  std::string file;
  std::string object;  ///< "/recording/t_s"
  Where at(std::string_view child) const {
    return {file, object == "/" ? "/" + std::string(child) : object + "/" + std::string(child)};
  }
};
[[noreturn]] void fail(const Where& w, const std::string& problem);

/// Turns HDF5's automatic error printing off (once per process): palp reports its own errors.
void silence_hdf5();

// --- writing -----------------------------------------------------------------------------------

Id create_group(hid_t parent, const Where& w);
/// A scalar attribute: a fixed-length UTF-8 string, a float64, an uint64 or an int64.
void put_attr(hid_t obj, const char* name, std::string_view text, const Where& w);
void put_attr(hid_t obj, const char* name, double value, const Where& w);
void put_attr(hid_t obj, const char* name, std::uint64_t value, const Where& w);
void put_attr(hid_t obj, const char* name, std::int64_t value, const Where& w);
/// A 1-D float64 attribute.
void put_attr(hid_t obj, const char* name, std::span<const double> values, const Where& w);

/// Typed copies of a JSON object's values as attributes named `prefix + key`: strings, numbers
/// (float64, uint64 or int64 as JSON has them) and non-empty number arrays (1-D float64); the
/// objects named in `descend` with `key + "."` as their prefix ("device.firmware_version");
/// anything else (null, booleans, other objects and arrays) is left out. A name that is already
/// an attribute is skipped.
void put_json_scalars(hid_t obj, const std::string& prefix, const nlohmann::json& object,
                      std::initializer_list<std::string_view> descend, const Where& w);

/// The file type of each column type: float64, uint64, uint16, int32 (little-endian).
template <class T> hid_t file_type();
template <class T> hid_t memory_type();

/// A 1-D dataset of `values`, chunked (at most 65536 rows a chunk), shuffled and deflated, with
/// its `unit` attribute. An empty one is contiguous (HDF5 chunks no empty extent).
template <class T>
void put_column(hid_t group, const char* name, std::span<const T> values, std::string_view unit,
                const Where& w);
/// A 2-D float64 dataset of `rows` x `columns` row-major `values` (a map's grid), chunked whole,
/// shuffled and deflated, with its `unit` attribute.
void put_grid(hid_t group, const char* name, std::span<const double> values, std::size_t rows,
              std::size_t columns, std::string_view unit, const Where& w);
/// A 2-D uint8 dataset of `rows` x `columns` row-major 0/1 `flags` (a map's measured mask), as
/// put_grid, with unit "1".
void put_mask_grid(hid_t group, const char* name, std::span<const std::uint8_t> flags,
                   std::size_t rows, std::size_t columns, const Where& w);

// --- reading -----------------------------------------------------------------------------------

bool has_attr(hid_t obj, const char* name);
bool has_link(hid_t group, const char* name);
/// A scalar string attribute; fail() when it is missing, not a string or longer than max_bytes.
std::string get_string_attr(hid_t obj, const char* name, const Where& w,
                            std::size_t max_bytes = 64u << 20);
Id open_group(hid_t parent, const char* name, const Where& w);

/// A 1-D dataset of exactly the type put_column writes for T, at most max_rows long.
template <class T>
std::vector<T> get_column(hid_t group, const char* name, std::uint64_t max_rows, const Where& w);

// --- the file ----------------------------------------------------------------------------------

/// Opens a palp HDF5 file read-only after checking its signature, its root palp_format (this
/// SDK's version) and content (== expected unless expected is empty). Returns the file.
Id open_palp_file(const std::filesystem::path& path, std::string_view expected_content,
                  std::string* content = nullptr);
/// Rows a column of `element_bytes` may claim in this file: what deflate could have packed into
/// its size (about 1030:1 at best), so a damaged extent cannot make the reader allocate more.
std::uint64_t max_rows(const std::filesystem::path& path, std::size_t element_bytes);

/// Writes `path` atomically: a hidden temporary file beside it gets the root attributes
/// (palp_format, content, sdk_version, created_utc), then `fill` writes into its root group; it
/// is flushed to disk and renamed to `path`. An existing `path` is refused with Overwrite::no and
/// replaced with Overwrite::yes only when it is a palp HDF5 file (ConfigError otherwise, checked
/// before and again just before the rename). On any error the temporary file is removed.
void write_palp_file(const std::filesystem::path& path, Overwrite overwrite,
                     std::string_view content, const std::function<void(hid_t root)>& fill);

}  // namespace palp::hdf5_detail
