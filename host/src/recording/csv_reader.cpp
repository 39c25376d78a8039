// SPDX-License-Identifier: Apache-2.0
// read_recording: the CSV in 1 MiB chunks, line by line (each at most format::kMaxLineBytes),
// each cell parsed where it lies (std::from_chars, no copies), every refusal with the file, the
// line and the problem; then the sidecar, checked against the CSV it claims to describe.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "palp/error.hpp"
#include "format/text_input.hpp"
#include "palp/recording.hpp"
#include "recording/internal.hpp"

namespace palp {
namespace rd = recording_detail;
namespace fs = std::filesystem;

namespace {

/// The file's lines, without their "\n" or "\r\n", numbered from 1; the CRC-32 of every byte.
/// A line stays valid until the next call to next(). A line longer than format::kMaxLineBytes
/// is refused as soon as that many bytes have no newline: memory stays at the 1 MiB buffer.
class LineReader {
 public:
  LineReader(const fs::path& path, const std::string& name) : name_(name) {
    file_ = std::fopen(path.c_str(), "rb");
    if (file_ == nullptr)
      throw RecordingError(name_, 0, std::string("cannot open: ") + std::strerror(errno));
    // the whole file when it is smaller than the buffer (a small file costs a small buffer)
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    buffer_.resize(ec ? kBuffer : std::clamp<std::size_t>(size + 1, 4096, kBuffer));
  }
  ~LineReader() { std::fclose(file_); }
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  bool next(std::string_view& line) {
    for (;;) {
      const char* begin = buffer_.data() + pos_;
      if (const void* nl = std::memchr(begin, '\n', end_ - pos_)) {
        const auto length = static_cast<std::size_t>(static_cast<const char*>(nl) - begin);
        pos_ += length + 1;
        return give(line, begin, length);
      }
      if (end_ - pos_ > format::kMaxLineBytes) {
        ++line_number_;
        throw RecordingError(name_, line_number_,
                             format::long_line_problem(std::string_view(begin, end_ - pos_)));
      }
      if (eof_) {
        if (pos_ == end_) return false;
        const std::size_t length = end_ - pos_;
        pos_ = end_;
        return give(line, begin, length);
      }
      fill();
    }
  }
  std::size_t line_number() const { return line_number_; }
  bool empty_file() const { return eof_ && total_bytes_ == 0; }
  /// Valid once next() has returned false.
  std::uint32_t crc32() const { return rd::Crc32::final(crc_state_); }

 private:
  bool give(std::string_view& line, const char* begin, std::size_t length) {
    if (length + 1 > format::kMaxLineBytes) {  // the newline counts
      ++line_number_;
      throw RecordingError(name_, line_number_,
                           format::long_line_problem(std::string_view(begin, length)));
    }
    if (length > 0 && begin[length - 1] == '\r') --length;
    line = std::string_view(begin, length);
    if (++line_number_ == 1 && line.starts_with("\xEF\xBB\xBF")) line.remove_prefix(3);
    return true;
  }
  void fill() {
    std::memmove(buffer_.data(), buffer_.data() + pos_, end_ - pos_);
    end_ -= pos_;
    pos_ = 0;
    // a file that grew, or reported no size: up to kBuffer, which holds any line allowed
    if (end_ == buffer_.size()) buffer_.resize(std::min(2 * buffer_.size(), kBuffer));
    const std::size_t got = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
    if (got == 0) {
      if (std::ferror(file_))
        throw RecordingError(name_, 0, std::string("cannot read: ") + std::strerror(errno));
      eof_ = true;
    }
    crc_state_ = rd::Crc32::update(crc_state_, buffer_.data() + end_, got);
    end_ += got;
    total_bytes_ += got;
  }

  static constexpr std::size_t kBuffer = 1u << 20;
  static_assert(kBuffer > format::kMaxLineBytes);
  const std::string& name_;
  std::FILE* file_ = nullptr;
  std::string buffer_;
  std::size_t pos_ = 0, end_ = 0, line_number_ = 0, total_bytes_ = 0;
  bool eof_ = false;
  std::uint32_t crc_state_ = rd::Crc32::kInit;
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

/// Comment ('#' first) or blank: not a row.
bool skipped(std::string_view line) {
  const std::string_view t = trim(line);
  return t.empty() || t.front() == '#';
}

void split(std::string_view line, char separator, std::vector<std::string_view>& fields) {
  fields.clear();
  for (;;) {
    const std::size_t at = line.find(separator);
    fields.push_back(trim(line.substr(0, at)));
    if (at == std::string_view::npos) return;
    line.remove_prefix(at + 1);
  }
}

enum class CellProblem { none, empty, decimal_comma, not_number, out_of_range, not_whole };

CellProblem parse_double(std::string_view s, double& out) {
  if (s.empty()) return CellProblem::empty;
  std::string_view body = s.front() == '+' ? s.substr(1) : s;
  // A number starts with a digit or a point, after one sign: "inf" and "nan" are not numbers.
  const std::size_t first = !body.empty() && body.front() == '-' && s.front() != '+' ? 1 : 0;
  if (body.size() <= first || !(is_digit(body[first]) || body[first] == '.'))
    return CellProblem::not_number;
  const char* end = body.data() + body.size();
  const auto r = std::from_chars(body.data(), end, out, std::chars_format::general);
  if (r.ec == std::errc::invalid_argument) return CellProblem::not_number;
  if (r.ptr != end)
    return *r.ptr == ',' && r.ptr + 1 < end && is_digit(r.ptr[1]) ? CellProblem::decimal_comma
                                                                  : CellProblem::not_number;
  return r.ec == std::errc::result_out_of_range ? CellProblem::out_of_range : CellProblem::none;
}

/// A whole number, also when written as a decimal ("3.0", "1e3").
template <class Int>
CellProblem parse_int(std::string_view s, Int& out) {
  if (s.empty()) return CellProblem::empty;
  const std::string_view body = s.front() == '+' ? s.substr(1) : s;
  const char* end = body.data() + body.size();
  const auto r = std::from_chars(body.data(), end, out);
  if (r.ptr == end && r.ec == std::errc()) return CellProblem::none;
  if (r.ptr == end && r.ec == std::errc::result_out_of_range) return CellProblem::out_of_range;
  double d = 0;
  if (const CellProblem p = parse_double(s, d); p != CellProblem::none) return p;
  if (d != std::floor(d)) return CellProblem::not_whole;
  // min and max + 1 are powers of two, exact as doubles.
  if (d < static_cast<double>(std::numeric_limits<Int>::min()) ||
      d >= static_cast<double>(std::numeric_limits<Int>::max()) + 1.0)
    return CellProblem::out_of_range;
  out = static_cast<Int>(d);
  return CellProblem::none;
}

template <class Int>
std::string int_range() {
  return "(" + std::to_string(std::numeric_limits<Int>::min()) + " to " +
         std::to_string(std::numeric_limits<Int>::max()) + ")";
}

std::string cell_text(std::string_view cell) { return format::quoted(cell); }

/// The names, comma-separated, each escaped and the whole cut (a header may be 64 KiB).
std::string join(const std::vector<std::string_view>& names) {
  std::string s;
  for (const std::string_view n : names) {
    s += (s.empty() ? "" : ", ") + format::escaped(n);
    if (s.size() > 4 * format::kQuoteChars) return s + ", \u2026";
  }
  return s;
}

/// Reads one CSV into a Recording; every problem is a RecordingError naming file and line.
class CsvReader {
 public:
  CsvReader(const fs::path& path, std::string name) : name_(std::move(name)), lines_(path, name_) {}

  Recording read() {
    read_header();
    std::vector<std::string_view> fields;
    std::string_view line;
    while (lines_.next(line)) {
      if (skipped(line)) continue;
      split(line, separator_, fields);
      if (fields.size() != field_columns_.size()) fail(wrong_field_count(fields.size()));
      for (std::size_t f = 0; f < fields.size(); ++f)
        if (field_columns_[f] >= 0) store(static_cast<Column>(field_columns_[f]), fields[f]);
      const double t = r_.t_s.back();
      if (r_.t_s.size() > 1 && t < r_.t_s[r_.t_s.size() - 2])
        fail("t_s decreases from " + rd::shortest(r_.t_s[r_.t_s.size() - 2]) + " to " +
             rd::shortest(t) + "; it must not decrease");
    }
    if (r_.size() == 0)
      throw RecordingError(name_, header_line_, "the header is not followed by any data row");
    crc32_ = lines_.crc32();
    return std::move(r_);
  }
  std::uint32_t crc32() const { return crc32_; }
  bool has_rep() const { return has_rep_; }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw RecordingError(name_, lines_.line_number(), problem);
  }

  void read_header() {
    std::string_view line;
    do {
      if (!lines_.next(line))
        throw RecordingError(name_, 0,
                             lines_.empty_file() ? "the file is empty; a recording starts with a "
                                                   "header row naming its columns (t_s, i_A, z_mm)"
                                                 : "the file has no header row, only comments");
    } while (skipped(line));
    header_line_ = lines_.line_number();
    separator_ = line.find('\t') != std::string_view::npos ? '\t' : ',';
    std::vector<std::string_view> names;
    split(line, separator_, names);
    bool seen[kColumnCount] = {};
    for (const std::string_view n : names) {
      int index = -1;
      for (std::size_t k = 0; k < kColumnCount; ++k)
        if (kColumnNames[k] == n) index = static_cast<int>(k);
      if (index >= 0) {
        if (seen[index]) fail("the column " + std::string(n) + " appears twice in the header");
        seen[index] = true;
      } else if (!n.empty()) {
        r_.ignored_columns.emplace_back(n);
      }
      field_columns_.push_back(index);
    }
    std::vector<std::string_view> missing;
    for (const Column c : {Column::t_s, Column::i_A, Column::z_mm})
      if (!seen[static_cast<std::size_t>(c)]) missing.push_back(column_name(c));
    if (!missing.empty()) {
      std::string problem =
          std::string("the header lacks the required column") + (missing.size() > 1 ? "s " : " ") +
          join(missing) + "; a recording needs t_s, i_A and z_mm (the header has: " + join(names) +
          ")";
      if (separator_ == ',' && line.find(';') != std::string_view::npos)
        problem += "; the columns look separated by semicolons, but a recording uses commas or "
                   "tabs";
      fail(problem);
    }
    if (!seen[static_cast<std::size_t>(Column::sample_index)]) r_.sample_index.reset();
    if (!seen[static_cast<std::size_t>(Column::i_cmd_A)]) r_.i_cmd_A.reset();
    for (std::size_t k = 0; k < r_.p_Pa.size(); ++k)
      if (!seen[static_cast<std::size_t>(pressure_column(k))]) r_.p_Pa[k].reset();
    if (!seen[static_cast<std::size_t>(Column::status)]) r_.status.reset();
    has_rep_ = seen[static_cast<std::size_t>(Column::rep)];
  }

  std::string wrong_field_count(std::size_t n) const {
    std::string s = std::to_string(n) + (n == 1 ? " field" : " fields") + " where the header has " +
                    std::to_string(field_columns_.size());
    if (separator_ == ',' && n > field_columns_.size())
      s += " (a decimal comma? numbers need a decimal point)";
    return s;
  }

  [[noreturn]] void bad_cell(Column c, std::string_view cell, CellProblem p,
                             const std::string& range) const {
    const std::string column = "column " + std::string(column_name(c));
    switch (p) {
      case CellProblem::empty: fail(column + " is empty");
      case CellProblem::decimal_comma: {
        std::string fixed(cell);
        fixed[fixed.find(',')] = '.';
        fail(column + ": " + cell_text(cell) +
             " has a decimal comma; numbers need a decimal point (" + format::escaped(fixed) +
             ")");
      }
      case CellProblem::not_whole: fail(column + ": " + cell_text(cell) + " is not a whole number");
      case CellProblem::out_of_range:
        fail(column + ": " + cell_text(cell) + " is out of range " + range);
      case CellProblem::not_number:
      case CellProblem::none: break;
    }
    fail(column + ": " + cell_text(cell) + " is not a number");
  }

  void store_double(Column c, std::string_view cell, std::vector<double>& column) {
    double v = 0;
    if (const CellProblem p = parse_double(cell, v); p != CellProblem::none)
      bad_cell(c, cell, p, "(beyond a double)");
    column.push_back(v);
  }
  template <class Int>
  void store_int(Column c, std::string_view cell, std::vector<Int>& column) {
    Int v = 0;
    if (const CellProblem p = parse_int(cell, v); p != CellProblem::none)
      bad_cell(c, cell, p, int_range<Int>());
    column.push_back(v);
  }

  void store(Column c, std::string_view cell) {
    switch (c) {
      case Column::sample_index: return store_int(c, cell, *r_.sample_index);
      case Column::t_s: return store_double(c, cell, r_.t_s);
      case Column::i_cmd_A: return store_double(c, cell, *r_.i_cmd_A);
      case Column::i_A: return store_double(c, cell, r_.i_A);
      case Column::z_mm: return store_double(c, cell, r_.z_mm);
      case Column::status: return store_int(c, cell, *r_.status);
      case Column::rep: return store_int(c, cell, r_.rep);
      default:
        return store_double(
            c, cell,
            *r_.p_Pa[static_cast<std::size_t>(c) - static_cast<std::size_t>(Column::p1_Pa)]);
    }
  }

  std::string name_;
  LineReader lines_;
  Recording r_;
  std::vector<int> field_columns_;  ///< per field: its Column, or -1 when not read
  std::size_t header_line_ = 0;
  char separator_ = ',';
  bool has_rep_ = false;
  std::uint32_t crc32_ = 0;
};

void check_sidecar_matches(const Sidecar& s, const fs::path& csv, const fs::path& sidecar_json,
                           std::uint64_t rows, std::uint32_t crc) {
  const std::string why =
      ": the two files are not from one write (a CSV edited by hand, or an overwrite that was "
      "interrupted); to load them anyway, read with "
      "ReadOptions{.check_sidecar_matches_csv = false}";
  const std::string csv_name = csv.filename().string();
  if (s.csv_rows && *s.csv_rows != rows)
    throw RecordingError(sidecar_json.string(), 0,
                         "\"csv_rows\" is " + std::to_string(*s.csv_rows) + ", but " + csv_name +
                             " has " + std::to_string(rows) + " data rows" + why);
  if (s.csv_crc32 && *s.csv_crc32 != crc)
    throw RecordingError(sidecar_json.string(), 0,
                         "\"csv_crc32\" is " + rd::crc32_hex(*s.csv_crc32) + ", but " + csv_name +
                             "'s CRC-32 is " + rd::crc32_hex(crc) + why);
}

}  // namespace

std::vector<std::size_t> recording_row_lines(const fs::path& csv) {
  const std::string name = csv.string();
  LineReader lines(csv, name);
  std::vector<std::size_t> rows;
  bool header = false;
  std::string_view line;
  while (lines.next(line)) {
    if (skipped(line)) continue;
    if (header) rows.push_back(lines.line_number());
    header = true;
  }
  return rows;
}

Recording read_recording(const fs::path& csv, const ReadOptions& options) {
  CsvReader reader(csv, csv.string());
  Recording r = reader.read();
  if (!reader.has_rep()) {
    r.rep = split_repetitions_at_current_minima(r.i_A);
    r.rep_source = RepSource::split_at_current_minima;
  }
  const fs::path sidecar_json = recording_sidecar_path(csv);
  if (options.read_sidecar && fs::exists(sidecar_json)) {
    Sidecar s = read_sidecar(sidecar_json);
    if (options.check_sidecar_matches_csv)
      check_sidecar_matches(s, csv, sidecar_json, r.size(), reader.crc32());
    r.sidecar = std::move(s);
  }
  return r;
}

}  // namespace palp
