// SPDX-License-Identifier: Apache-2.0
// The HDF5 C API behind palp/hdf5.hpp (h5.hpp).
#include "hdf5/h5.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <mutex>
#include <type_traits>

#include "format/text_input.hpp"
#include "palp/error.hpp"
#include "palp/hdf5.hpp"
#include "palp/probe.hpp"
#include "recording/internal.hpp"

namespace palp::hdf5_detail {

namespace fs = std::filesystem;

void fail(const Where& w, const std::string& problem) {
  throw RecordingError(w.file, 0, (w.object.empty() ? "" : w.object + ": ") + problem);
}

void silence_hdf5() {
  static std::once_flag once;
  std::call_once(once, [] { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); });
}

namespace {

hid_t check(hid_t id, const Where& w, const char* what) {
  if (id < 0) fail(w, std::string("HDF5 cannot ") + what);
  return id;
}
void check(herr_t r, const Where& w, const char* what, int) {
  if (r < 0) fail(w, std::string("HDF5 cannot ") + what);
}

/// A fixed-length UTF-8 string type of `bytes` bytes (at least 1), NUL-padded. Not a
/// variable-length string: HDF5 1.10 keeps those in the global heap, and reading a damaged one
/// crashes or hangs inside the library (docs/hdf5-format.md "Reading").
Id utf8_string_type(std::size_t bytes, const Where& w) {
  Id t(check(H5Tcopy(H5T_C_S1), w, "make a string type"), H5Tclose);
  check(H5Tset_size(t.get(), std::max<std::size_t>(bytes, 1)), w, "make a string type", 0);
  check(H5Tset_strpad(t.get(), H5T_STR_NULLPAD), w, "make a string type", 0);
  check(H5Tset_cset(t.get(), H5T_CSET_UTF8), w, "make a string type", 0);
  return t;
}

void put_scalar_attr(hid_t obj, const char* name, hid_t file_t, hid_t mem_t, const void* value,
                     const Where& w) {
  Id space(check(H5Screate(H5S_SCALAR), w, "make a dataspace"), H5Sclose);
  Id a(check(H5Acreate2(obj, name, file_t, space.get(), H5P_DEFAULT, H5P_DEFAULT), w.at(name),
             "create the attribute"),
       H5Aclose);
  check(H5Awrite(a.get(), mem_t, value), w.at(name), "write the attribute", 0);
}

}  // namespace

Id create_group(hid_t parent, const Where& w) {
  const std::string name = w.object.substr(w.object.rfind('/') + 1);
  return Id(check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), w,
                  "create the group"),
            H5Gclose);
}

void put_attr(hid_t obj, const char* name, std::string_view text, const Where& w) {
  const Id t = utf8_string_type(text.size(), w);
  std::string padded(text);
  padded.resize(std::max<std::size_t>(text.size(), 1), '\0');
  put_scalar_attr(obj, name, t.get(), t.get(), padded.data(), w);
}
void put_attr(hid_t obj, const char* name, double value, const Where& w) {
  put_scalar_attr(obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, w);
}
void put_attr(hid_t obj, const char* name, std::uint64_t value, const Where& w) {
  put_scalar_attr(obj, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &value, w);
}
void put_attr(hid_t obj, const char* name, std::int64_t value, const Where& w) {
  put_scalar_attr(obj, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value, w);
}
void put_attr(hid_t obj, const char* name, std::span<const double> values, const Where& w) {
  const hsize_t n = values.size();
  Id space(check(H5Screate_simple(1, &n, nullptr), w, "make a dataspace"), H5Sclose);
  Id a(check(H5Acreate2(obj, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), w.at(name),
             "create the attribute"),
       H5Aclose);
  check(H5Awrite(a.get(), H5T_NATIVE_DOUBLE, values.data()), w.at(name), "write the attribute", 0);
}

void put_json_scalars(hid_t g, const std::string& prefix, const nlohmann::json& object,
                      std::initializer_list<std::string_view> descend, const Where& w) {
  for (const auto& [key, v] : object.items()) {
    const std::string name = prefix + key;
    if (has_attr(g, name.c_str())) continue;
    if (v.is_object()) {
      if (std::find(descend.begin(), descend.end(), key) != descend.end())
        put_json_scalars(g, name + ".", v, {}, w);
    } else if (v.is_string()) {
      put_attr(g, name.c_str(), v.get<std::string>(), w);
    } else if (v.is_number_unsigned()) {
      put_attr(g, name.c_str(), v.get<std::uint64_t>(), w);
    } else if (v.is_number_integer()) {
      put_attr(g, name.c_str(), v.get<std::int64_t>(), w);
    } else if (v.is_number_float()) {
      put_attr(g, name.c_str(), v.get<double>(), w);
    } else if (v.is_array() && !v.empty() &&
               std::all_of(v.begin(), v.end(), [](const nlohmann::json& e) { return e.is_number(); })) {
      std::vector<double> values;
      for (const auto& e : v) values.push_back(e.get<double>());
      put_attr(g, name.c_str(), std::span<const double>(values), w);
    }
  }
}

template <> hid_t file_type<double>() { return H5T_IEEE_F64LE; }
template <> hid_t file_type<std::uint64_t>() { return H5T_STD_U64LE; }
template <> hid_t file_type<std::uint16_t>() { return H5T_STD_U16LE; }
template <> hid_t file_type<int>() { return H5T_STD_I32LE; }
template <> hid_t memory_type<double>() { return H5T_NATIVE_DOUBLE; }
template <> hid_t memory_type<std::uint64_t>() { return H5T_NATIVE_UINT64; }
template <> hid_t memory_type<std::uint16_t>() { return H5T_NATIVE_UINT16; }
template <> hid_t memory_type<int>() { return H5T_NATIVE_INT; }

namespace {

/// A dataset of `rank` dimensions `dims` (values row-major), chunked (`chunk`) and filtered unless
/// it is empty, with its `unit` attribute.
void put_dataset(hid_t group, const char* name, hid_t file_t, hid_t mem_t, const void* values, int rank,
                 const hsize_t* dims, const hsize_t* chunk, std::string_view unit, const Where& w) {
  Id space(check(H5Screate_simple(rank, dims, nullptr), w, "make a dataspace"), H5Sclose);
  Id dcpl(check(H5Pcreate(H5P_DATASET_CREATE), w, "make a dataset property list"), H5Pclose);
  hsize_t n = 1;
  for (int k = 0; k < rank; ++k) n *= dims[k];
  if (n > 0) {
    check(H5Pset_chunk(dcpl.get(), rank, chunk), w, "set the chunk size", 0);
    check(H5Pset_shuffle(dcpl.get()), w, "set the shuffle filter", 0);
    check(H5Pset_deflate(dcpl.get(), 4), w, "set the deflate filter", 0);
  }
  Id d(check(H5Dcreate2(group, name, file_t, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), w,
             "create the dataset"),
       H5Dclose);
  if (n > 0)
    check(H5Dwrite(d.get(), mem_t, H5S_ALL, H5S_ALL, H5P_DEFAULT, values), w, "write the dataset", 0);
  put_attr(d.get(), "unit", unit, w);
}

}  // namespace

template <class T>
void put_column(hid_t group, const char* name, std::span<const T> values, std::string_view unit,
                const Where& w_group) {
  const hsize_t n = values.size();
  const hsize_t chunk = std::min<hsize_t>(std::max<hsize_t>(n, 1), 65536);
  put_dataset(group, name, file_type<T>(), memory_type<T>(), values.data(), 1, &n, &chunk, unit, w_group.at(name));
}
void put_grid(hid_t group, const char* name, std::span<const double> values, std::size_t rows,
              std::size_t columns, std::string_view unit, const Where& w_group) {
  const Where w = w_group.at(name);
  if (values.size() != rows * columns)
    fail(w, std::to_string(values.size()) + " values for a " + std::to_string(rows) + " x " +
                std::to_string(columns) + " grid");
  const hsize_t dims[2] = {rows, columns};
  put_dataset(group, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, values.data(), 2, dims, dims, unit, w);
}
void put_mask_grid(hid_t group, const char* name, std::span<const std::uint8_t> flags,
                   std::size_t rows, std::size_t columns, const Where& w_group) {
  const Where w = w_group.at(name);
  if (flags.size() != rows * columns)
    fail(w, std::to_string(flags.size()) + " flags for a " + std::to_string(rows) + " x " +
                std::to_string(columns) + " grid");
  const hsize_t dims[2] = {rows, columns};
  put_dataset(group, name, H5T_STD_U8LE, H5T_NATIVE_UINT8, flags.data(), 2, dims, dims, "1", w);
}
template void put_column<double>(hid_t, const char*, std::span<const double>, std::string_view, const Where&);
template void put_column<std::uint64_t>(hid_t, const char*, std::span<const std::uint64_t>, std::string_view, const Where&);
template void put_column<std::uint16_t>(hid_t, const char*, std::span<const std::uint16_t>, std::string_view, const Where&);
template void put_column<int>(hid_t, const char*, std::span<const int>, std::string_view, const Where&);

bool has_attr(hid_t obj, const char* name) { return H5Aexists(obj, name) > 0; }
bool has_link(hid_t group, const char* name) { return H5Lexists(group, name, H5P_DEFAULT) > 0; }

std::string get_string_attr(hid_t obj, const char* name, const Where& w_obj, std::size_t max_bytes) {
  const Where w = w_obj.at(name);
  if (!has_attr(obj, name)) fail(w_obj, std::string("the attribute ") + name + " is missing");
  Id a(check(H5Aopen(obj, name, H5P_DEFAULT), w, "open the attribute"), H5Aclose);
  Id ft(check(H5Aget_type(a.get()), w, "read the attribute's type"), H5Tclose);
  Id space(check(H5Aget_space(a.get()), w, "read the attribute's shape"), H5Sclose);
  if (H5Tget_class(ft.get()) != H5T_STRING || H5Tis_variable_str(ft.get()) != 0 ||
      H5Sget_simple_extent_type(space.get()) != H5S_SCALAR)
    fail(w, "is not a single fixed-length string");
  const std::size_t size = H5Tget_size(ft.get());
  if (size == 0 || size > max_bytes)
    fail(w, "has " + std::to_string(size) + " bytes, more than the limit of " + std::to_string(max_bytes));
  std::string text(size, '\0');
  check(H5Aread(a.get(), ft.get(), text.data()), w, "read the attribute (damaged?)");
  text.resize(std::strlen(text.c_str()));  // the NUL padding
  return text;
}

Id open_group(hid_t parent, const char* name, const Where& w_parent) {
  const Where w = w_parent.at(name);
  if (!has_link(parent, name)) fail(w_parent, std::string("the group ") + name + " is missing");
  H5O_info_t info{};
  if (H5Oget_info_by_name2(parent, name, &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0 ||
      info.type != H5O_TYPE_GROUP)
    fail(w, "is not a group");
  return Id(check(H5Gopen2(parent, name, H5P_DEFAULT), w, "open the group"), H5Gclose);
}

template <class T>
std::vector<T> get_column(hid_t group, const char* name, std::uint64_t max_rows, const Where& w_group) {
  const Where w = w_group.at(name);
  if (!has_link(group, name)) fail(w_group, std::string("the dataset ") + name + " is missing");
  Id d(check(H5Dopen2(group, name, H5P_DEFAULT), w, "open the dataset"), H5Dclose);
  Id ft(check(H5Dget_type(d.get()), w, "read the dataset's type"), H5Tclose);
  if (H5Tequal(ft.get(), file_type<T>()) <= 0) {
    fail(w, std::string("has the wrong type; palp writes it as ") +
                (std::is_floating_point_v<T> ? "float64" : std::is_signed_v<T> ? "int32"
                 : sizeof(T) == 8 ? "uint64" : "uint16") + " (little-endian)");
  }
  Id space(check(H5Dget_space(d.get()), w, "read the dataset's shape"), H5Sclose);
  if (H5Sget_simple_extent_ndims(space.get()) != 1) fail(w, "is not a 1-D column");
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space.get(), &n, nullptr);
  if (n > max_rows)
    fail(w, "claims " + std::to_string(n) + " rows, more than the file's size can hold (damaged?)");
  std::vector<T> values(static_cast<std::size_t>(n));
  if (n > 0)
    check(H5Dread(d.get(), memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), w,
          "read the dataset (damaged?)", 0);
  return values;
}
template std::vector<double> get_column<double>(hid_t, const char*, std::uint64_t, const Where&);
template std::vector<std::uint64_t> get_column<std::uint64_t>(hid_t, const char*, std::uint64_t, const Where&);
template std::vector<std::uint16_t> get_column<std::uint16_t>(hid_t, const char*, std::uint64_t, const Where&);
template std::vector<int> get_column<int>(hid_t, const char*, std::uint64_t, const Where&);

std::uint64_t max_rows(const fs::path& path, std::size_t element_bytes) {
  std::error_code ec;
  const std::uint64_t size = fs::file_size(path, ec);
  if (ec) return 0;
  return (size * 1100u + (1u << 20)) / std::max<std::size_t>(element_bytes, 1);
}

namespace {

/// An existing file palp may replace: a regular file that is a palp HDF5 file (any version).
bool is_palp_hdf5(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(path, ec)) || !is_hdf5_file(path)) return false;
  Id f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!f.valid() || !has_attr(f.get(), "palp_format")) return false;
  try {
    return get_string_attr(f.get(), "palp_format", {path.string(), "/"}).rfind("palp.hdf5/", 0) == 0;
  } catch (const RecordingError&) {
    return false;
  }
}

void check_target(const fs::path& path, Overwrite overwrite) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(path, ec))) return;
  if (overwrite == Overwrite::no)
    throw ConfigError(path.string() + " already exists; choose another name, or overwrite it");
  if (!is_palp_hdf5(path))
    throw ConfigError(path.string() +
                      " exists and palp did not write it (not an HDF5 file with palp_format): "
                      "nothing was replaced; move it away, or choose another name");
}

}  // namespace

Id open_palp_file(const fs::path& path, std::string_view expected_content, std::string* content_out) {
  silence_hdf5();
  const Where root{path.string(), "/"};
  std::error_code ec;
  if (!fs::exists(path, ec)) throw RecordingError(path.string(), 0, "no such file");
  if (!fs::is_regular_file(path, ec)) throw RecordingError(path.string(), 0, "not a regular file");
  if (!is_hdf5_file(path))
    throw RecordingError(path.string(), 0, "not an HDF5 file (it does not start with HDF5's signature)");
  Id f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!f.valid()) throw RecordingError(path.string(), 0, "HDF5 cannot open it (damaged or truncated?)");
  if (!has_attr(f.get(), "palp_format"))
    throw RecordingError(path.string(), 0, "an HDF5 file, but not one palp wrote (no palp_format attribute on /)");
  const std::string version = get_string_attr(f.get(), "palp_format", root, 256);
  if (version != kHdf5Format)
    throw RecordingError(path.string(), 0,
                         "palp_format is \"" + format::escaped(version) + "\", this SDK reads \"" +
                             std::string(kHdf5Format) +
                             (version.rfind("palp.hdf5/", 0) == 0 ? "\"; update the SDK" : "\""));
  const std::string content = get_string_attr(f.get(), "content", root, 256);
  if (!expected_content.empty() && content != expected_content)
    throw RecordingError(path.string(), 0,
                         "holds a " + format::escaped(content) + ", not a " + std::string(expected_content));
  if (content_out != nullptr) *content_out = content;
  return f;
}

void write_palp_file(const fs::path& path, Overwrite overwrite, std::string_view content,
                     const std::function<void(hid_t root)>& fill) {
  silence_hdf5();
  check_target(path, overwrite);
  const fs::path tmp = recording_detail::temporary_sibling(path);
  const Where root{path.string(), "/"};
  std::error_code ec;
  try {
    {
      // the 1.8 file format at least: an attribute over 64 KiB (a long sidecar) is stored densely
      Id fapl(check(H5Pcreate(H5P_FILE_ACCESS), root, "make a file access property list"), H5Pclose);
      check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST), root, "set the file format", 0);
      Id f(H5Fcreate(tmp.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl.get()), H5Fclose);
      if (!f.valid()) throw RecordingError(path.string(), 0, "cannot create " + tmp.string());
      put_attr(f.get(), "palp_format", kHdf5Format, root);
      put_attr(f.get(), "content", content, root);
      put_attr(f.get(), "sdk_version", std::string_view(sdk_version()), root);
      put_attr(f.get(), "created_utc", recording_detail::utc_now(), root);
      fill(f.get());
      if (H5Fflush(f.get(), H5F_SCOPE_GLOBAL) < 0) fail(root, "cannot flush the file");
      if (H5Fclose(f.release()) < 0) fail(root, "cannot close the file");
    }
    const int fd = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
    const bool synced = fd >= 0 && ::fsync(fd) == 0;
    if (fd >= 0) ::close(fd);
    if (!synced) throw RecordingError(path.string(), 0, "cannot flush " + tmp.string() + " to disk");
    check_target(path, overwrite);  // again: a file may have appeared while this one was written
    fs::rename(tmp, path);
    recording_detail::sync_directory(path.parent_path());
  } catch (const fs::filesystem_error& e) {
    fs::remove(tmp, ec);
    throw RecordingError(path.string(), 0, "cannot put the file in place: " + e.code().message());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace palp::hdf5_detail

namespace palp {

bool is_hdf5_file(const std::filesystem::path& path) {
  static constexpr std::array<char, 8> kSignature = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
  std::ifstream in(path, std::ios::binary);
  std::array<char, 8> head{};
  if (!in.read(head.data(), head.size())) return false;
  return head == kSignature;
}

}  // namespace palp
