// SPDX-License-Identifier: Apache-2.0
// Reading the rig and plan files: one JSON object, keys checked one by one, every error one
// line "file: key: problem" (syntax errors "file:line:column: problem").
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "format/field_table.hpp"
#include <string_view>
#include <vector>

namespace palp::rig_detail {

class Fields {
 public:
  /// Parses text (ConfigError on a syntax error or a top level that is not an object) and
  /// rejects keys outside `known`.
  Fields(std::string_view text, std::string source, const std::vector<std::string>& known);
  /// A nested object under key (rejecting keys outside known), named "key.sub" in errors.
  Fields(const Fields& parent, const std::string& key, const std::vector<std::string>& known);

  bool has(const std::string& key) const;
  std::string text(const std::string& key) const;
  /// A number within [lo, hi] (hi_open: < hi), unit for messages.
  double number(const std::string& key, double lo, double hi, std::string_view unit) const;
  double positive(const std::string& key, double hi, std::string_view unit) const;
  int integer(const std::string& key, int lo, int hi) const;
  std::vector<double> numbers(const std::string& key, std::size_t count) const;
  bool boolean(const std::string& key) const;
  /// [x_mm, y_mm, z_mm, a_deg, b_deg, c_deg]: positions within +-100 m, angles within +-360 deg.
  Pose pose(const std::string& key) const;
  // a field table's Source (format/field_table.hpp): the range's checks and unit
  double number(const std::string& key, const format::Range& r) const;
  long long integer(const std::string& key, const format::Range& r) const;
  /// The table's keys (and `more`): every other key in the object is unknown.
  template <class T, std::size_t N>
  static std::vector<std::string> keys(const format::Field<T> (&table)[N],
                                       std::vector<std::string> more = {}) {
    for (const auto& f : table) more.emplace_back(f.key);
    return more;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;
  void require(const std::vector<std::string>& keys) const;

 private:
  const nlohmann::json& at(const std::string& key) const;
  std::string source_;
  std::string prefix_;  // "" or "parent."
  nlohmann::json json_;
};

/// Reads a whole file; ConfigError "file: cannot read (reason)".
std::string read_file(const std::string& path);

}  // namespace palp::rig_detail
