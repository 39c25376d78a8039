// SPDX-License-Identifier: Apache-2.0
// Frequency-response tables: the two CSV layouts with an optional sigma column (see
// frf_table.hpp). Every refusal is a RecordingError naming the file, the line and the problem.
#include "palp/analysis/frf_table.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <numbers>
#include <vector>

#include "format/text_input.hpp"
#include "palp/error.hpp"
#include "number_text.hpp"

namespace palp::analysis {

namespace {

constexpr const char* kLayouts =
    "a frequency-response table starts with the header f_Hz,re_m_per_N,im_m_per_N or "
    "f_Hz,mag_m_per_N,phase_deg, optionally followed by sigma_m_per_N";

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> cells;
  for (;;) {
    const std::size_t at = line.find(',');
    cells.push_back(trim(line.substr(0, at)));
    if (at == std::string_view::npos) return cells;
    line.remove_prefix(at + 1);
  }
}

/// A finite number written as one ("inf", "nan", "1e999" and trailing text are not).
bool parse_number(std::string_view s, double& out) {
  if (s.empty()) return false;
  if (s.front() == '+') s.remove_prefix(1);
  const std::size_t first = !s.empty() && s.front() == '-' ? 1 : 0;
  if (s.size() <= first || !((s[first] >= '0' && s[first] <= '9') || s[first] == '.')) return false;
  const char* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, out, std::chars_format::general);
  return r.ec == std::errc() && r.ptr == end && std::isfinite(out);
}

enum class Layout { re_im, mag_phase };

class TableParser {
 public:
  TableParser(std::string_view text, std::string name) : text_(text), name_(std::move(name)) {}

  Frf parse() {
    read_header();
    std::string_view line;
    while (next(line)) row(line);
    if (frf_.lines.size() < 3)
      throw RecordingError(name_, 0,
                           "the table has " + std::to_string(frf_.lines.size()) +
                               (frf_.lines.size() == 1 ? " row" : " rows") +
                               "; a frequency response needs at least 3");
    finish();
    return std::move(frf_);
  }

 private:
  /// The next row that is not blank or a comment; false at the end.
  bool next(std::string_view& line) {
    while (pos_ < text_.size()) {
      const std::size_t nl = text_.find('\n', pos_);
      const std::size_t end = nl == std::string_view::npos ? text_.size() : nl;
      line = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++line_;
      if (line.size() + 1 > format::kMaxLineBytes) fail(format::long_line_problem(line));
      if (line_ == 1 && line.starts_with("\xEF\xBB\xBF")) line.remove_prefix(3);
      const std::string_view t = trim(line);
      if (!t.empty() && t.front() != '#') return true;
    }
    return false;
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw RecordingError(name_, line_, problem);
  }

  void read_header() {
    std::string_view line;
    if (!next(line)) throw RecordingError(name_, 0, std::string("no header row; ") + kLayouts);
    header_ = split(line);
    const std::size_t n = header_.size();
    const bool sigma = n == 4 && header_[3] == "sigma_m_per_N";
    if ((n == 3 || sigma) && header_[0] == "f_Hz") {
      if (header_[1] == "re_m_per_N" && header_[2] == "im_m_per_N") layout_ = Layout::re_im;
      else if (header_[1] == "mag_m_per_N" && header_[2] == "phase_deg") layout_ = Layout::mag_phase;
      else unknown_header(line);
      has_sigma_ = sigma;
      return;
    }
    unknown_header(line);
  }
  [[noreturn]] void unknown_header(std::string_view line) const {
    fail("unknown header " + format::quoted(trim(line)) + "; " + kLayouts);
  }

  void row(std::string_view line) {
    const std::vector<std::string_view> cells = split(line);
    if (cells.size() != header_.size())
      fail(std::to_string(cells.size()) + (cells.size() == 1 ? " cell" : " cells") +
           " where the header has " + std::to_string(header_.size()) +
           (cells.size() > header_.size() ? " (a decimal comma? numbers need a decimal point)"
                                          : ""));
    double v[4] = {};
    for (std::size_t c = 0; c < cells.size(); ++c)
      if (!parse_number(cells[c], v[c]))
        fail("column " + std::string(header_[c]) + ": " + format::quoted(cells[c]) +
             " is not a finite number");
    FrfLine l;
    l.f_Hz = v[0];
    if (l.f_Hz <= 0) fail("f_Hz must be positive (got " + detail::number_text(l.f_Hz) + ")");
    if (!frf_.lines.empty() && l.f_Hz <= frf_.lines.back().f_Hz)
      fail("f_Hz " + detail::number_text(l.f_Hz) + " does not increase (the row before has " +
           detail::number_text(frf_.lines.back().f_Hz) + ")");
    if (layout_ == Layout::re_im) {
      l.G_m_per_N = {v[1], v[2]};
    } else {
      if (v[1] < 0) fail("mag_m_per_N must not be negative (got " + detail::number_text(v[1]) + ")");
      l.G_m_per_N = std::polar(v[1], v[2] * std::numbers::pi / 180.0);
    }
    if (has_sigma_) {
      if (v[3] < 0) fail("sigma_m_per_N must not be negative (got " + detail::number_text(v[3]) + ")");
      l.sigma_m_per_N = v[3];
    }
    frf_.lines.push_back(l);
  }

  void finish() {
    frf_.method = "table";
    const std::size_t n = frf_.lines.size();
    frf_.line_spacing_Hz = (frf_.lines.back().f_Hz - frf_.lines.front().f_Hz) / static_cast<double>(n - 1);
    std::size_t positive = 0;
    for (const FrfLine& l : frf_.lines)
      if (l.G_m_per_N.imag() > 0) ++positive;
    if (2 * positive > n)
      frf_.notes.push_back(
          std::to_string(positive) + " of the " + std::to_string(n) + " Im G values of " + name_ +
          " are positive: the table probably uses the opposite sign convention (a passive system "
          "has Im G <= 0 with x = Re{X e^{jwt}}); the data are used as they are");
  }

  std::string_view text_;
  std::string name_;
  std::size_t pos_ = 0, line_ = 0;
  std::vector<std::string_view> header_;
  Layout layout_ = Layout::re_im;
  bool has_sigma_ = false;
  Frf frf_;
};

}  // namespace

Frf parse_frf_table(std::string_view text, const std::string& name) {
  return TableParser(text, name).parse();
}

Frf read_frf_table(const std::filesystem::path& csv) {
  const std::string name = csv.string();
  const std::string text = format::read_bounded_or(
      csv, format::kMaxTableFileBytes,
      [&](const std::string& problem) -> void { throw RecordingError(name, 0, problem); });
  return parse_frf_table(text, name);
}

bool is_frf_table(const std::filesystem::path& file) {
  std::FILE* f = std::fopen(file.c_str(), "rb");
  if (f == nullptr)
    throw RecordingError(file.string(), 0, std::string("cannot open: ") + std::strerror(errno));
  std::string line;
  bool table = false, first = true;
  // a row (neither blank nor a comment) decides; a line is looked at up to kMaxLineBytes
  const auto decides = [&] {
    std::string_view t = line;
    if (first && t.starts_with("\xEF\xBB\xBF")) t.remove_prefix(3);
    first = false;
    t = trim(t);
    if (t.empty() || t.front() == '#') return false;
    table = t.starts_with("f_Hz");
    return true;
  };
  bool decided = false;
  for (int c = 0; !decided && (c = std::fgetc(f)) != EOF;) {
    if (c != '\n' && line.size() < format::kMaxLineBytes) {
      line += static_cast<char>(c);
      continue;
    }
    decided = decides();
    line.clear();
  }
  if (!decided) decides();  // the last line, without a newline
  std::fclose(f);
  return table;
}

}  // namespace palp::analysis
