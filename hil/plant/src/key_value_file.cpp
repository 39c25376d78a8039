// SPDX-License-Identifier: Apache-2.0
// The phantom files' key = value parser (see key_value_file.hpp).
#include "key_value_file.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "palp/plant/phantom.hpp"

namespace palp::plant::detail {
namespace {

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

bool valid_key(std::string_view key) {
  if (key.empty()) return false;
  for (char ch : key) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                    (ch >= '0' && ch <= '9') || ch == '_';
    if (!ok) return false;
  }
  return true;
}

std::vector<std::string_view> split_commas(std::string_view value) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const auto comma = value.find(',', start);
    out.push_back(trim(value.substr(start, comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

std::string format_number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

}  // namespace

KeyValueFile KeyValueFile::parse(std::string_view text, std::string source) {
  KeyValueFile f;
  f.source_ = std::move(source);
  int line_no = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const auto nl = text.find('\n', pos);
    const std::string_view raw =
        text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    ++line_no;
    std::string_view line = raw.substr(0, raw.find('#'));
    line = trim(line);
    if (!line.empty()) {
      const auto eq = line.find('=');
      if (eq == std::string_view::npos) f.fail(line_no, "expected 'key = value'");
      const std::string_view key = trim(line.substr(0, eq));
      const std::string_view value = trim(line.substr(eq + 1));
      if (!valid_key(key)) f.fail(line_no, "bad key '" + std::string(key) + "'");
      if (value.empty()) f.fail(line_no, "no value for '" + std::string(key) + "'");
      if (const Entry* prev = f.find(key)) {
        f.fail(line_no, "duplicate key '" + std::string(key) + "' (first at line " +
                            std::to_string(prev->line) + ")");
      }
      f.entries_.push_back({std::string(key), std::string(value), line_no});
    }
    if (nl == std::string_view::npos || nl + 1 == text.size()) break;  // no empty last line
    pos = nl + 1;
  }
  f.last_line_ = line_no;
  return f;
}

void KeyValueFile::fail(int line, const std::string& problem) const {
  throw PhantomError(source_ + ":" + std::to_string(line) + ": " + problem);
}

const KeyValueFile::Entry* KeyValueFile::find(std::string_view key) const {
  for (const Entry& e : entries_) {
    if (e.key == key) return &e;
  }
  return nullptr;
}

const KeyValueFile::Entry& KeyValueFile::get(std::string_view key) const {
  const Entry* e = find(key);
  if (!e) fail(last_line_, "missing required key '" + std::string(key) + "'");
  return *e;
}

int KeyValueFile::line_of(std::string_view key) const {
  const Entry* e = find(key);
  return e ? e->line : last_line_;
}

void KeyValueFile::reject_unknown(const std::vector<std::string_view>& known,
                                  std::string_view context) const {
  for (const Entry& e : entries_) {
    bool ok = false;
    for (std::string_view k : known) ok = ok || (e.key == k);
    if (!ok) fail(e.line, "unknown key '" + e.key + "' (" + std::string(context) + ")");
  }
}

void KeyValueFile::require(const std::vector<std::string_view>& required,
                           std::string_view context) const {
  for (std::string_view k : required) {
    if (!find(k)) {
      fail(last_line_,
           "missing required key '" + std::string(k) + "' (" + std::string(context) + ")");
    }
  }
}

std::string KeyValueFile::word(std::string_view key,
                               std::initializer_list<std::string_view> allowed) const {
  const Entry& e = get(key);
  if (allowed.size() == 0) return e.value;
  std::string list;
  for (std::string_view a : allowed) {
    if (e.value == a) return e.value;
    list += (list.empty() ? "" : " | ") + std::string(a);
  }
  fail(e.line, "bad value '" + e.value + "' for '" + e.key + "' (expected " + list + ")");
}

double KeyValueFile::parse_number(const Entry& e, std::string_view token, double lo,
                                  double hi) const {
  double v = 0.0;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (!token.empty() && *first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (token.empty() || ec != std::errc() || ptr != last || !std::isfinite(v)) {
    fail(e.line, "bad number '" + std::string(token) + "' for '" + e.key + "'");
  }
  if (v < lo || v > hi) {
    fail(e.line, "'" + e.key + "' = " + std::string(token) + " is out of range [" +
                     format_number(lo) + ", " + format_number(hi) + "]");
  }
  return v;
}

double KeyValueFile::number(std::string_view key, double lo, double hi) const {
  const Entry& e = get(key);
  return parse_number(e, e.value, lo, hi);
}

std::vector<double> KeyValueFile::numbers(std::string_view key, std::size_t count, double lo,
                                          double hi) const {
  const Entry& e = get(key);
  const auto tokens = split_commas(e.value);
  if (tokens.size() != count) {
    fail(e.line, "'" + e.key + "' needs " + std::to_string(count) + " values, got " +
                     std::to_string(tokens.size()));
  }
  std::vector<double> out;
  out.reserve(count);
  for (std::string_view t : tokens) out.push_back(parse_number(e, t, lo, hi));
  return out;
}

int KeyValueFile::integer(std::string_view key, int lo, int hi) const {
  return integers(key, 1, lo, hi).front();
}

std::vector<int> KeyValueFile::integers(std::string_view key, std::size_t count, int lo,
                                        int hi) const {
  const Entry& e = get(key);
  const auto values = numbers(key, count, lo, hi);
  std::vector<int> out;
  out.reserve(count);
  for (double v : values) {
    if (v != std::floor(v)) fail(e.line, "'" + e.key + "' needs whole numbers");
    out.push_back(static_cast<int>(v));
  }
  return out;
}

}  // namespace palp::plant::detail
