// SPDX-License-Identifier: Apache-2.0
// Fields: checked access to the rig and plan files' JSON objects.
#include "json_fields.hpp"

#include <cmath>
#include <sstream>

#include "format/text_input.hpp"
#include "palp/error.hpp"

namespace palp::rig_detail {
namespace {

std::string format_number(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

// nlohmann's parse_error text without its "[json.exception...] parse error at ...: " prefix.
std::string short_reason(const std::string& what) {
  const auto col = what.find("column ");
  const auto colon = what.find(": ", col == std::string::npos ? 0 : col);
  return colon == std::string::npos ? what : what.substr(colon + 2);
}

}  // namespace

Fields::Fields(std::string_view text, std::string source, const std::vector<std::string>& known)
    : source_(std::move(source)) {
  try {
    json_ = nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is 1-based: the byte at which the parser stopped.
    const std::size_t stop = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < stop; ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    throw ConfigError(source_ + ":" + std::to_string(line) + ":" + std::to_string(column) +
                      ": JSON syntax error: " +
                      format::escaped(short_reason(e.what()), 4 * format::kQuoteChars));
  } catch (const nlohmann::json::exception& e) {  // out_of_range: a number beyond a double
    throw ConfigError(source_ + ": JSON error: " +
                      format::escaped(e.what(), 4 * format::kQuoteChars));
  }
  if (!json_.is_object()) throw ConfigError(source_ + ": the top level must be a JSON object");
  for (const auto& item : json_.items()) {
    bool ok = false;
    for (const auto& k : known) ok = ok || item.key() == k;
    if (!ok) fail(item.key(), "unknown key");
  }
}

Fields::Fields(const Fields& parent, const std::string& key, const std::vector<std::string>& known)
    : source_(parent.source_), prefix_(parent.prefix_ + key + ".") {
  const nlohmann::json& j = parent.at(key);
  if (!j.is_object()) parent.fail(key, "must be a JSON object");
  json_ = j;
  for (const auto& item : json_.items()) {
    bool ok = false;
    for (const auto& k : known) ok = ok || item.key() == k;
    if (!ok) fail(item.key(), "unknown key");
  }
}

void Fields::fail(const std::string& key, const std::string& problem) const {
  throw ConfigError(source_ + ": " + prefix_ + format::escaped(key) + ": " + problem);
}

bool Fields::has(const std::string& key) const { return json_.contains(key); }

void Fields::require(const std::vector<std::string>& keys) const {
  for (const auto& k : keys) {
    if (!has(k)) fail(k, "missing (required)");
  }
}

const nlohmann::json& Fields::at(const std::string& key) const {
  if (!has(key)) fail(key, "missing (required)");
  return json_.at(key);
}

std::string Fields::text(const std::string& key) const {
  const nlohmann::json& j = at(key);
  if (!j.is_string()) fail(key, "must be a string");
  const std::string s = j.get<std::string>();
  if (s.empty()) fail(key, "must not be empty");
  return s;
}

double Fields::number(const std::string& key, double lo, double hi, std::string_view unit) const {
  const nlohmann::json& j = at(key);
  if (!j.is_number()) fail(key, "must be a number");
  const double v = j.get<double>();
  if (!std::isfinite(v) || v < lo || v > hi) {
    fail(key, "must be in " + format_number(lo) + ".." + format_number(hi) + " " +
                  std::string(unit) + " (got " + format_number(v) + ")");
  }
  return v;
}

double Fields::positive(const std::string& key, double hi, std::string_view unit) const {
  const double v = number(key, -INFINITY, hi, unit);
  if (!(v > 0.0)) fail(key, "must be > 0 " + std::string(unit) + " (got " + format_number(v) + ")");
  return v;
}

int Fields::integer(const std::string& key, int lo, int hi) const {
  const nlohmann::json& j = at(key);
  if (!j.is_number_integer()) fail(key, "must be an integer");
  const auto v = j.get<long long>();
  if (v < lo || v > hi) {
    fail(key, "must be in " + std::to_string(lo) + ".." + std::to_string(hi) + " (got " +
                  std::to_string(v) + ")");
  }
  return static_cast<int>(v);
}

std::vector<double> Fields::numbers(const std::string& key, std::size_t count) const {
  const nlohmann::json& j = at(key);
  if (!j.is_array() || j.size() != count) {
    fail(key, "must be an array of " + std::to_string(count) + " numbers");
  }
  std::vector<double> out;
  for (const auto& e : j) {
    if (!e.is_number() || !std::isfinite(e.get<double>())) {
      fail(key, "must be an array of " + std::to_string(count) + " numbers");
    }
    out.push_back(e.get<double>());
  }
  return out;
}

bool Fields::boolean(const std::string& key) const {
  const nlohmann::json& j = at(key);
  if (!j.is_boolean()) fail(key, "must be true or false");
  return j.get<bool>();
}

Pose Fields::pose(const std::string& key) const {
  const std::vector<double> v = numbers(key, 6);
  for (std::size_t k = 3; k < 6; ++k)
    if (std::abs(v[k]) > 360.0) fail(key, "angles must be within +-360 deg");
  for (std::size_t k = 0; k < 3; ++k)
    if (std::abs(v[k]) > 1e5) fail(key, "positions must be within +-100 m");
  return format::pose_of_mm_deg({v[0], v[1], v[2], v[3], v[4], v[5]});
}

double Fields::number(const std::string& key, const format::Range& r) const {
  return r.positive ? positive(key, r.hi, r.unit) : number(key, r.lo, r.hi, r.unit);
}

long long Fields::integer(const std::string& key, const format::Range& r) const {
  return integer(key, static_cast<int>(r.lo), static_cast<int>(r.hi));
}

std::string read_file(const std::string& path) {
  return format::read_bounded_or(path, format::kMaxJsonFileBytes, [&](const std::string& problem) {
    throw ConfigError(path + ": " + problem);
  });
}

}  // namespace palp::rig_detail
