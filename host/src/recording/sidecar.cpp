// SPDX-License-Identifier: Apache-2.0
// The sidecar (run.json): written in the documented key order, read back with every unknown key
// kept, and refused with a message that names the key when a known key has the wrong type.
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "format/text_input.hpp"
#include "palp/error.hpp"
#include "palp/recording.hpp"
#include "recording/internal.hpp"

namespace palp {
namespace rd = recording_detail;
using nlohmann::json;
using nlohmann::ordered_json;

namespace {

constexpr std::array<std::string_view, 11> kKnownKeys = {
    "schema",  "sdk_version", "created_utc",        "program",
    "device",  "calibration", "stroke_origin_z_mm", "stroke_origin_z_mm_reason",
    "zeroing", "csv_rows",    "csv_crc32"};
/// The `<key>_reason` of a null object key, when the caller gave none.
constexpr std::string_view kDefaultReason = "not given to the recording writer";
constexpr std::string_view kSchemaPrefix = "palp.recording/";

bool is_known_key(std::string_view key) {
  return std::find(kKnownKeys.begin(), kKnownKeys.end(), key) != kKnownKeys.end();
}

std::string in_quotes(std::string_view key) { return format::quoted(key); }

/// Reads the sidecar's keys, throwing RecordingError(file, 0, ...) for the first bad one.
class SidecarParser {
 public:
  SidecarParser(const json& doc, const std::string& file) : doc_(doc), file_(file) {}

  Sidecar parse() {
    if (!doc_.is_object()) fail("the sidecar must be a JSON object, not " + rd::json_kind(doc_));
    check_schema();
    Sidecar s;
    s.sdk_version = string_key("sdk_version", /*required=*/true);
    s.created_utc = string_key("created_utc", /*required=*/false);
    s.program = object_or_null_key("program");
    s.device = object_or_null_key("device");
    s.calibration = object_or_null_key("calibration");
    read_stroke_origin(s);
    read_zeroing(s);
    read_csv_check(s);
    for (const auto& [key, value] : doc_.items())
      if (!is_known_key(key)) s.extra[key] = value;
    return s;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw RecordingError(file_, 0, problem);
  }
  [[noreturn]] void wrong_type(std::string_view key, const std::string& expected,
                               const json& value) const {
    fail(in_quotes(key) + " must be " + expected + ", not " + rd::json_kind(value));
  }
  const json* find(std::string_view key) const {
    const auto it = doc_.find(key);
    return it == doc_.end() ? nullptr : &*it;
  }

  void check_schema() const {
    const json* v = find("schema");
    if (v == nullptr)
      fail("the key \"schema\" is missing; a palp recording sidecar has \"schema\": " +
           in_quotes(kRecordingSchema));
    if (!v->is_string()) wrong_type("schema", "a string", *v);
    const std::string& text = v->get_ref<const std::string&>();
    unsigned major = 0;
    const char* first = text.data() + std::min(text.size(), kSchemaPrefix.size());
    const char* last = text.data() + text.size();
    const auto r = std::from_chars(first, last, major);
    if (!text.starts_with(kSchemaPrefix) || r.ec != std::errc() || r.ptr != last)
      fail("\"schema\" is " + in_quotes(text) + ", not " + in_quotes(kRecordingSchema) +
           ": this is not a palp recording sidecar");
    if (major != 1)
      fail("\"schema\" is " + in_quotes(text) + ", which this SDK cannot read (it reads " +
           std::string(kRecordingSchema) + "); update the SDK");
  }

  std::string string_key(std::string_view key, bool required) const {
    const json* v = find(key);
    if (v == nullptr) {
      if (required) fail("the key " + in_quotes(key) + " is missing");
      return {};
    }
    if (!v->is_string()) wrong_type(key, "a string", *v);
    return v->get<std::string>();
  }

  json object_or_null_key(std::string_view key) const {
    const json* v = find(key);
    if (v == nullptr) return nullptr;
    if (!v->is_object() && !v->is_null()) wrong_type(key, "an object or null", *v);
    return *v;
  }

  void read_stroke_origin(Sidecar& s) const {
    const json* v = find("stroke_origin_z_mm");
    if (v == nullptr)
      fail(
          "the key \"stroke_origin_z_mm\" is missing (a number, or null with "
          "\"stroke_origin_z_mm_reason\")");
    if (v->is_number()) {
      s.stroke_origin_z_mm = v->get<double>();
    } else if (!v->is_null()) {
      wrong_type("stroke_origin_z_mm", "a number or null", *v);
    }
    s.stroke_origin_z_mm_reason = string_key("stroke_origin_z_mm_reason", false);
    if (v->is_null() && s.stroke_origin_z_mm_reason.empty())
      fail("\"stroke_origin_z_mm\" is null without a \"stroke_origin_z_mm_reason\" saying why");
  }

  void read_zeroing(Sidecar& s) const {
    const json* v = find("zeroing");
    if (v == nullptr) return;  // nothing was zeroed
    if (!v->is_array()) wrong_type("zeroing", "an array", *v);
    for (std::size_t k = 0; k < v->size(); ++k)
      if (!(*v)[k].is_object())
        wrong_type("zeroing[" + std::to_string(k) + "]", "an object", (*v)[k]);
    s.zeroing = *v;
  }

  void read_csv_check(Sidecar& s) const {
    if (const json* v = find("csv_rows")) {
      if (!v->is_number_unsigned()) wrong_type("csv_rows", "a whole number >= 0", *v);
      s.csv_rows = v->get<std::uint64_t>();
    }
    if (const json* v = find("csv_crc32")) {
      const auto crc =
          v->is_string() ? rd::parse_crc32_hex(v->get_ref<const std::string&>()) : std::nullopt;
      if (!crc) wrong_type("csv_crc32", "a string of 8 hex digits", *v);
      s.csv_crc32 = crc;
    }
  }

  const json& doc_;
  const std::string& file_;
};

}  // namespace

std::string rd::json_kind(const json& value) {
  const std::string text = format::escaped(value.dump());  // DEL and UTF-8 pass dump() as they are
  switch (value.type()) {
    case json::value_t::null: return "null";
    case json::value_t::object: return "an object";
    case json::value_t::array: return "an array";
    case json::value_t::string: return "a string (" + text + ")";
    case json::value_t::boolean: return "a boolean (" + text + ")";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: return "a number (" + text + ")";
    case json::value_t::binary: return "binary data";
    case json::value_t::discarded: break;
  }
  return "nothing";
}

std::string rd::crc32_hex(std::uint32_t crc) {
  char buf[9];
  std::snprintf(buf, sizeof buf, "%08x", static_cast<unsigned>(crc));
  return buf;
}

std::optional<std::uint32_t> rd::parse_crc32_hex(std::string_view text) {
  if (text.size() != 8) return std::nullopt;
  std::uint32_t crc = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), crc, 16);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size()) return std::nullopt;
  return crc;
}

ordered_json rd::sidecar_document(const Sidecar& s) {
  if (!s.extra.is_object())
    throw ConfigError("Sidecar::extra must be a JSON object, not " + json_kind(s.extra));
  for (const auto& item : s.extra.items())
    if (is_known_key(item.key()))
      throw ConfigError("Sidecar::extra holds the key " + in_quotes(item.key()) +
                        ", which the sidecar writes from its own field; set that field instead");

  ordered_json d;
  d["schema"] = kRecordingSchema;
  d["sdk_version"] = s.sdk_version;
  d["created_utc"] = s.created_utc;
  std::vector<std::string> reasons_written;
  const auto object_or_null = [&](const std::string& key, const json& value) {
    if (!value.is_null() && !value.is_object())
      throw ConfigError("Sidecar::" + key + " must be a JSON object or null, not " +
                        json_kind(value));
    d[key] = ordered_json(value);
    const std::string reason_key = key + "_reason";
    if (const auto it = s.extra.find(reason_key); it != s.extra.end()) {
      d[reason_key] = ordered_json(*it);
      reasons_written.push_back(reason_key);
    } else if (value.is_null()) {
      d[reason_key] = kDefaultReason;
    }
  };
  object_or_null("program", s.program);
  object_or_null("device", s.device);
  object_or_null("calibration", s.calibration);

  if (s.stroke_origin_z_mm) {
    if (!std::isfinite(*s.stroke_origin_z_mm))
      throw ConfigError("Sidecar::stroke_origin_z_mm is " + shortest(*s.stroke_origin_z_mm) +
                        "; use nullopt with a stroke_origin_z_mm_reason when it is unknown");
    d["stroke_origin_z_mm"] = *s.stroke_origin_z_mm;
  } else {
    d["stroke_origin_z_mm"] = nullptr;
    d["stroke_origin_z_mm_reason"] = s.stroke_origin_z_mm_reason.empty()
                                         ? std::string(kDefaultReason)
                                         : s.stroke_origin_z_mm_reason;
  }

  if (!s.zeroing.is_array())
    throw ConfigError("Sidecar::zeroing must be a JSON array, not " + json_kind(s.zeroing));
  for (std::size_t k = 0; k < s.zeroing.size(); ++k)
    if (!s.zeroing[k].is_object())
      throw ConfigError("Sidecar::zeroing[" + std::to_string(k) + "] must be a JSON object, not " +
                        json_kind(s.zeroing[k]));
  d["zeroing"] = ordered_json(s.zeroing);
  if (s.csv_rows) d["csv_rows"] = *s.csv_rows;
  if (s.csv_crc32) d["csv_crc32"] = crc32_hex(*s.csv_crc32);

  for (const auto& item : s.extra.items())
    if (std::find(reasons_written.begin(), reasons_written.end(), item.key()) ==
        reasons_written.end())
      d[item.key()] = ordered_json(item.value());
  return d;
}

json sidecar_to_json(const Sidecar& sidecar) { return json(rd::sidecar_document(sidecar)); }

Sidecar sidecar_from_json(const json& doc, const std::string& file) {
  return SidecarParser(doc, file).parse();
}

Sidecar read_sidecar(const std::filesystem::path& json_path) {
  const std::string file = json_path.string();
  const std::string text = format::read_bounded_or(
      json_path, format::kMaxJsonFileBytes,
      [&](const std::string& problem) -> void { throw RecordingError(file, 0, problem); });
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    // e.byte counts the characters read, the offending one included.
    const std::size_t at = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    const std::size_t line =
        1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + at, '\n'));
    const std::size_t newline = at == 0 ? std::string::npos : text.rfind('\n', at - 1);
    const std::size_t column = newline == std::string::npos ? at + 1 : at - newline;
    // nlohmann's text: "[json.exception.parse_error.101] parse error at line L, column C: what".
    std::string what = e.what();
    if (const auto colon = what.find(": ", what.find("column")); colon != std::string::npos)
      what = what.substr(colon + 2);
    throw RecordingError(file, line,
                         "not valid JSON at column " + std::to_string(column) + ": " +
                             format::escaped(what, 4 * format::kQuoteChars));
  } catch (const json::exception& e) {  // out_of_range: a number beyond a double (1e999)
    throw RecordingError(file, 0,
                         "not valid JSON: " + format::escaped(e.what(), 4 * format::kQuoteChars));
  }
  return sidecar_from_json(doc, file);
}

void to_json(json& doc, const Sidecar& sidecar) { doc = sidecar_to_json(sidecar); }
void from_json(const json& doc, Sidecar& sidecar) { sidecar = sidecar_from_json(doc); }

}  // namespace palp
