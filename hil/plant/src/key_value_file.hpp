// SPDX-License-Identifier: Apache-2.0
// KeyValueFile: the small parser under the phantom files. Lines are "key = value  # comment";
// values are a word, a number or a comma-separated list of numbers. Every error is a
// PhantomError with a one-line message "source:line: problem". Private to palp_plant.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace palp::plant::detail {

class KeyValueFile {
 public:
  /// Split text into entries; rejects lines without '=', bad keys, empty values, duplicates.
  static KeyValueFile parse(std::string_view text, std::string source);

  const std::string& source() const { return source_; }
  bool has(std::string_view key) const { return find(key) != nullptr; }

  /// Throw PhantomError "source:line: problem".
  [[noreturn]] void fail(int line, const std::string& problem) const;
  /// Line of key (or the last line when absent), for messages about its value.
  int line_of(std::string_view key) const;

  /// Reject the first key not in `known` ("unknown key 'x' (context)").
  void reject_unknown(const std::vector<std::string_view>& known, std::string_view context) const;
  /// Reject the first absent key of `required` ("missing required key 'x' (context)"), reported
  /// at the file's last line.
  void require(const std::vector<std::string_view>& required, std::string_view context) const;

  /// A word from `allowed` (or any non-empty word when allowed is empty).
  std::string word(std::string_view key, std::initializer_list<std::string_view> allowed) const;
  /// One finite number within [lo, hi].
  double number(std::string_view key, double lo, double hi) const;
  /// Exactly `count` finite numbers within [lo, hi], comma-separated.
  std::vector<double> numbers(std::string_view key, std::size_t count, double lo, double hi) const;
  /// One integer within [lo, hi].
  int integer(std::string_view key, int lo, int hi) const;
  /// Exactly `count` integers within [lo, hi].
  std::vector<int> integers(std::string_view key, std::size_t count, int lo, int hi) const;

 private:
  struct Entry {
    std::string key;
    std::string value;
    int line = 0;
  };

  const Entry* find(std::string_view key) const;
  const Entry& get(std::string_view key) const;
  double parse_number(const Entry& e, std::string_view token, double lo, double hi) const;

  std::string source_;
  std::vector<Entry> entries_;
  int last_line_ = 0;
};

}  // namespace palp::plant::detail
