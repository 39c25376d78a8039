// SPDX-License-Identifier: Apache-2.0
// Field tables: a file format's keys defined once. Each entry names a key, the struct member it
// holds, the scale from the member's SI unit to the file's lab unit, whether a file must have it
// and, for numbers, the range a reader accepts. The writer (write_fields) and the reader
// (read_fields) walk the same table, as protocol/include/palp/protocol/catalogue.hpp does for
// the wire, so a key, its unit and its member cannot drift apart between the two.
//
//   const format::Field<Rig> kRigFields[] = {
//       {"robot_uri", &Rig::robot_uri},
//       {"safe_height_mm", &Rig::safe_height_m, format::kMm, format::Need::required, {0, 1000, true}},
//       ...};
//   format::write_fields(j, rig, kRigFields);          // j["safe_height_mm"] = safe_height_m * 1e3
//   format::read_fields(source, rig, kRigFields);      // safe_height_m = file value / 1e3
//
// A member is a double, an optional double (null in the file when absent; with Need::or_null a
// double too may be null, with `<key>_reason`), an int, a uint32, a size_t or uint64
// (JsonSource::count reads it exactly), a bool, a string, a Pose (the file's [x_mm, y_mm, z_mm,
// a_deg, b_deg, c_deg]), a vector of doubles (an array, each element scaled; the Source's
// numbers(key) reads it), or a protocol message's float (written as its shortest decimal, f32)
// or uint16. The file value is the SI value times the scale; the reader undoes it with one
// rounding (from_file). The reader takes a Source, the format's checked access to one JSON
// object with its own error messages (JsonSource below for "where: \"key\" must be a number";
// rig_detail::Fields for the rig and plan files' "file: key: problem" with ranges).
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "palp/error.hpp"
#include "palp/pose.hpp"

namespace palp::format {

inline constexpr double kMm = 1e3;        ///< m -> mm
inline constexpr double kNPerMm = 1e-3;   ///< N/m -> N/mm
inline constexpr double kDeg = 180.0 / std::numbers::pi;  ///< rad -> deg

enum class Need {
  required,  ///< a file without the key (or with null) is an error
  optional,  ///< absent or null: the member keeps its default (an optional double: none)
  written,   ///< written only: derived again on reading (the reader skips it)
  /// A number, or null with `<key>_reason` (DESIGN.md: never NaN in a file). Written: a double
  /// that is not finite, or an optional double without a value, as null with `<key>_reason` =
  /// the entry's null_reason. Read: a number; null back into what the writer had, none for an
  /// optional double and NaN for a double (a caller that needs the value says so with the
  /// file's reason: JsonSource::reason).
  or_null,
};

/// The values a reader accepts for a number: [lo, hi], or (0, hi] when positive.
struct Range {
  double lo = -INFINITY, hi = INFINITY;
  bool positive = false;
  const char* unit = "";
};

/// A file value back in SI: divided by a scale of 1 or more, else times its exact inverse (the
/// N/mm scale 1e-3 is no exact double; its inverse 1e3 is).
inline double from_file(double file_value, double scale) {
  return scale >= 1.0 ? file_value / scale : file_value * (1.0 / scale);
}

template <class T>
struct Field {
  // unsigned long and unsigned long long: size_t and uint64_t, whichever of the two each is on
  // the platform (both unsigned long on 64-bit Linux, distinct on macOS and Windows).
  using Member = std::variant<double T::*, std::optional<double> T::*, int T::*, std::uint32_t T::*,
                              unsigned long T::*, unsigned long long T::*, bool T::*, std::string T::*,
                              Pose T::*, std::vector<double> T::*, float T::*, std::uint16_t T::*>;
  const char* key;
  Member member;
  double scale = 1.0;  ///< file value = SI value x scale
  Need need = Need::required;
  Range range{};
  const char* null_reason = "not finite";  ///< Need::or_null: `<key>_reason` when written null
};

/// The shortest decimal of a protocol f32 as a double (0.01f is written 0.01, not 0.009999999776).
inline double f32(float v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  double d = 0;
  std::from_chars(buf, r.ptr, d);
  return d;
}

/// A pose in the files' form: [x_mm, y_mm, z_mm, a_deg, b_deg, c_deg].
inline nlohmann::json pose_mm_deg(const Pose& p) {
  return nlohmann::json::array(
      {p.x_m * kMm, p.y_m * kMm, p.z_m * kMm, p.a_rad * kDeg, p.b_rad * kDeg, p.c_rad * kDeg});
}
inline Pose pose_of_mm_deg(const double (&v)[6]) {
  return Pose{v[0] / kMm, v[1] / kMm, v[2] / kMm, v[3] / kDeg, v[4] / kDeg, v[5] / kDeg};
}

/// j[key] = v when v is a finite number, else null and j["<key>_reason"] = why_not (Need::or_null).
template <class Json>
void put_or_null(Json& j, const std::string& key, std::optional<double> v, const char* why_not = "not finite") {
  if (v && std::isfinite(*v)) {
    j[key] = *v;
  } else {
    j[key] = nullptr;
    j[key + "_reason"] = why_not;
  }
}

/// Every field of `table` into j (nlohmann::json, or ordered_json: the table's order is then the
/// file's order).
template <class Json, class T>
void write_fields(Json& j, const T& v, std::span<const Field<T>> table) {
  for (const Field<T>& f : table) {
    std::visit(
        [&](auto member) {
          using M = std::remove_cvref_t<decltype(v.*member)>;
          const M& x = v.*member;
          if constexpr (std::is_same_v<M, double> || std::is_same_v<M, std::optional<double>>) {
            if (f.need == Need::or_null) {
              const std::optional<double> o(x);
              put_or_null(j, f.key, o ? std::optional<double>(*o * f.scale) : std::nullopt, f.null_reason);
              return;
            }
          }
          if constexpr (std::is_same_v<M, double>) j[f.key] = x * f.scale;
          else if constexpr (std::is_same_v<M, float>) j[f.key] = f32(x) * f.scale;
          else if constexpr (std::is_same_v<M, std::optional<double>>) j[f.key] = x ? Json(*x * f.scale) : Json(nullptr);
          else if constexpr (std::is_same_v<M, Pose>) j[f.key] = pose_mm_deg(x);
          else if constexpr (std::is_same_v<M, std::vector<double>>) {
            Json a = Json::array();
            for (double e : x) a.push_back(e * f.scale);
            j[f.key] = std::move(a);
          } else j[f.key] = x;
        },
        f.member);
  }
}
template <class Json, class T, std::size_t N>
void write_fields(Json& j, const T& v, const Field<T> (&table)[N]) {
  write_fields(j, v, std::span<const Field<T>>(table));
}

/// Every field of `table` but the Need::written ones from `src`, a format's checked access to a
/// JSON object: has(key) (present and not null), number(key, range), integer(key, range),
/// boolean(key), text(key) and, where the format has them, pose(key), numbers(key) (a vector
/// of doubles) and is_null(key) (Need::or_null), each throwing its ConfigError
/// when the key is absent or the value is not of its kind or range. An optional key that is absent is skipped.
// GCC 12 sees the visit's store into an optional<double> member of a struct that holds none (the
// alternative is instantiated for every table) as a write past its end: a false positive.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstringop-overflow"
#endif
template <class Source, class T>
void read_fields(const Source& src, T& v, std::span<const Field<T>> table) {
  for (const Field<T>& f : table) {
    if (f.need == Need::written) continue;
    if (f.need == Need::optional && !src.has(f.key)) continue;
    if (f.need == Need::or_null) {
      if constexpr (requires { src.is_null(f.key); }) {
        if (src.is_null(f.key)) {
          std::visit(
              [&](auto member) {
                using M = std::remove_cvref_t<decltype(v.*member)>;
                if constexpr (std::is_same_v<M, std::optional<double>>) v.*member = std::nullopt;
                else if constexpr (std::is_same_v<M, double>) v.*member = NAN;
                else throw ConfigError(std::string(f.key) + ": only a number may be null");
              },
              f.member);
          continue;
        }
      } else {
        throw ConfigError(std::string(f.key) + ": this format's reader takes no nulls");
      }
    }
    std::visit(
        [&](auto member) {
          using M = std::remove_cvref_t<decltype(v.*member)>;
          M& x = v.*member;
          if constexpr (std::is_same_v<M, double> || std::is_same_v<M, std::optional<double>>)
            x = from_file(src.number(f.key, f.range), f.scale);
          else if constexpr (std::is_same_v<M, int>) x = static_cast<int>(src.integer(f.key, f.range));
          else if constexpr (std::is_same_v<M, float>)
            x = static_cast<float>(from_file(src.number(f.key, f.range), f.scale));
          else if constexpr (std::is_same_v<M, unsigned long> || std::is_same_v<M, unsigned long long>) {
            if constexpr (requires { src.count(f.key); }) x = static_cast<M>(src.count(f.key));
            else x = static_cast<M>(src.integer(f.key, f.range));
          } else if constexpr (std::is_same_v<M, std::uint32_t> || std::is_same_v<M, std::uint16_t>)
            x = static_cast<M>(src.integer(f.key, f.range));
          else if constexpr (std::is_same_v<M, bool>) x = src.boolean(f.key);
          else if constexpr (std::is_same_v<M, std::string>) x = src.text(f.key);
          else if constexpr (std::is_same_v<M, std::vector<double>>) {
            if constexpr (requires { src.numbers(f.key); }) {
              x.clear();
              for (double e : src.numbers(f.key)) x.push_back(from_file(e, f.scale));
            } else {
              throw ConfigError(std::string(f.key) + ": this format's reader takes no arrays");
            }
          } else if constexpr (requires { src.pose(f.key); }) x = src.pose(f.key);
          else throw ConfigError(std::string(f.key) + ": this format's reader takes no poses");
        },
        f.member);
  }
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
template <class Source, class T, std::size_t N>
void read_fields(const Source& src, T& v, const Field<T> (&table)[N]) {
  read_fields(src, v, std::span<const Field<T>>(table));
}

/// How a JsonSource names a bad key.
enum class Naming {
  where_colon_key,  ///< "where: \"key\" must be a number"; an absent key reads as null
  dotted_path,      ///< result.json's "\"parameters.key\" is not a number", "missing key \"parameters.key\""
};

/// A JSON object's Source: ConfigError naming the key (Naming); an integer is any number,
/// truncated, as the trace and map readers always took it; no ranges.
class JsonSource {
 public:
  JsonSource(const nlohmann::json& j, std::string where, Naming naming = Naming::where_colon_key)
      : j_(j), where_(std::move(where)), naming_(naming) {}
  bool has(const char* key) const {
    const auto it = j_.find(key);
    return it != j_.end() && !it->is_null();
  }
  /// Present and null (Need::or_null).
  bool is_null(const char* key) const {
    const auto it = j_.find(key);
    return it != j_.end() && it->is_null();
  }
  /// `<key>_reason`, the text beside a null (Need::or_null); "no reason given" without one.
  std::string reason(const char* key) const {
    const auto it = j_.find(std::string(key) + "_reason");
    return it != j_.end() && it->is_string() ? it->get<std::string>() : "no reason given";
  }
  double number(const char* key, const Range&) const {
    const auto& v = at(key);
    if (!v.is_number()) wrong(key, "a number");
    return v.get<double>();
  }
  long long integer(const char* key, const Range& r) const {
    return static_cast<long long>(number(key, r));
  }
  /// A count (a size_t or uint64 member): a non-negative integer, read exactly.
  std::uint64_t count(const char* key) const {
    const auto& v = at(key);
    if (v.is_number_unsigned()) return v.get<std::uint64_t>();
    if (v.is_number_integer() && v.get<std::int64_t>() >= 0) return static_cast<std::uint64_t>(v.get<std::int64_t>());
    if (v.is_number_float() && v.get<double>() >= 0 && v.get<double>() < 0x1p64 &&
        v.get<double>() == std::floor(v.get<double>()))
      return static_cast<std::uint64_t>(v.get<double>());  // 3.0: a count another writer wrote as a float
    wrong(key, "a non-negative integer");
  }
  bool boolean(const char* key) const {
    const auto& v = at(key);
    if (!v.is_boolean()) wrong(key, "true or false");
    return v.get<bool>();
  }
  std::string text(const char* key) const {
    const auto& v = at(key);
    if (!v.is_string()) wrong(key, "a string");
    return v.get<std::string>();
  }
  std::vector<double> numbers(const char* key) const {
    const auto& v = at(key);
    if (!v.is_array()) wrong(key, "an array of numbers");
    std::vector<double> out;
    for (const auto& e : v) {
      if (!e.is_number()) wrong(key, "an array of numbers");
      out.push_back(e.get<double>());
    }
    return out;
  }
  const nlohmann::json& object(const char* key) const {
    const auto& v = at(key);
    if (!v.is_object()) wrong(key, "an object");
    return v;
  }
  Pose pose(const char* key) const {
    const auto& v = at(key);
    const std::string what = where_ + ": " + key;
    if (!v.is_array() || v.size() != 6)
      throw ConfigError(what + ": expected [x_mm, y_mm, z_mm, a_deg, b_deg, c_deg]");
    double x[6];
    for (std::size_t k = 0; k < 6; ++k) {
      if (!v[k].is_number()) throw ConfigError(what + ": every element must be a number");
      x[k] = v[k].get<double>();
    }
    return pose_of_mm_deg(x);
  }
  /// ConfigError naming the key with `problem` ("must be ...") after it.
  [[noreturn]] void fail(const char* key, const std::string& problem) const {
    if (naming_ == Naming::dotted_path) throw ConfigError("\"" + where_ + key + "\" " + problem);
    throw ConfigError(where_ + ": \"" + key + "\" " + problem);
  }

 private:
  [[noreturn]] void wrong(const char* key, const char* kind) const {
    fail(key, std::string(naming_ == Naming::dotted_path ? "is not " : "must be ") + kind);
  }
  /// The value; when the key is absent null (where_colon_key) or ConfigError (dotted_path).
  const nlohmann::json& at(const char* key) const {
    static const nlohmann::json null;
    const auto it = j_.find(key);
    if (it != j_.end()) return *it;
    if (naming_ == Naming::dotted_path) throw ConfigError("missing key \"" + where_ + key + "\"");
    return null;
  }
  const nlohmann::json& j_;
  std::string where_;
  Naming naming_;
};

}  // namespace palp::format
