// SPDX-License-Identifier: Apache-2.0
// Bounded reading of the text files palp reads (recordings, frequency-response tables, sidecars,
// result, trace, rig and plan JSON), and the one way an error message quotes their contents.
//
// Limits (docs/reliability.md §4 lists them with the formats that carry them):
//   - a line of a CSV file (recording, frequency-response table): at most kMaxLineBytes;
//   - a file read whole (every JSON file, a frequency-response table): at most its kind's limit.
// A file over a limit is refused as soon as the limit is passed (a 1 GB file without a newline
// costs one 1 MiB buffer, never the file), naming the file, the line and the limit.
//
// Quoting: at most kQuoteChars bytes of the input, then "…"; every byte outside printable ASCII
// (control bytes, DEL, and bytes of multi-byte characters) written as \xNN, so nothing a file
// holds reaches the terminal as a control sequence and a quote is one line.
#pragma once

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>

namespace palp::format {

/// The longest line a CSV reader accepts, its "\r\n" included (a recording row is < 200 bytes).
inline constexpr std::size_t kMaxLineBytes = 64 * 1024;
/// The largest JSON file read (sidecar, result.json, trace.json, rig, plan, compare files).
inline constexpr std::size_t kMaxJsonFileBytes = 64u << 20;
/// The largest frequency-response table (read whole; ~300 000 rows).
inline constexpr std::size_t kMaxTableFileBytes = 16u << 20;
/// How many bytes of input an error message quotes.
inline constexpr std::size_t kQuoteChars = 60;

/// "65536 bytes (64 KiB)": a limit as the messages and the docs say it.
inline std::string bytes_text(std::size_t n) {
  std::string s = std::to_string(n) + " bytes";
  if (n >= (1u << 20) && n % (1u << 20) == 0) return s + " (" + std::to_string(n >> 20) + " MiB)";
  if (n >= 1024 && n % 1024 == 0) return s + " (" + std::to_string(n >> 10) + " KiB)";
  return s;
}

/// The input cut to max bytes (then "…") with every byte outside printable ASCII as \xNN.
inline std::string escaped(std::string_view text, std::size_t max = kQuoteChars) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (std::size_t k = 0; k < std::min(text.size(), max); ++k) {
    const auto c = static_cast<unsigned char>(text[k]);
    if (c >= 0x20 && c < 0x7F) {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 0xF];
    }
  }
  if (text.size() > max) out += "\u2026";
  return out;
}

/// escaped() in double quotes: how an error message quotes a cell, a key or a line.
inline std::string quoted(std::string_view text, std::size_t max = kQuoteChars) {
  return "\"" + escaped(text, max) + "\"";
}

/// A whole file of at most limit bytes, read without trusting its size (a FIFO or /dev/zero
/// stops at limit + 1 bytes). On a problem returns false with problem set ("cannot open: ...",
/// "the file is larger than the limit of ...").
inline bool read_bounded(const std::filesystem::path& path, std::size_t limit, std::string& text,
                         std::string& problem) {
  text.clear();
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    problem = std::string("cannot open: ") + std::strerror(errno);
    return false;
  }
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > limit) {
    std::fclose(f);
    problem = "the file has " + std::to_string(size) + " bytes, more than the limit of " +
              bytes_text(limit);
    return false;
  }
  char buf[1 << 16];
  bool ok = true;
  for (;;) {
    const std::size_t got = std::fread(buf, 1, sizeof buf, f);
    if (got == 0) {
      if (std::ferror(f)) {
        problem = std::string("cannot read: ") + std::strerror(errno);
        ok = false;
      }
      break;
    }
    if (text.size() + got > limit) {
      problem = "the file is larger than the limit of " + bytes_text(limit);
      ok = false;
      break;
    }
    text.append(buf, got);
  }
  std::fclose(f);
  if (!ok) text.clear();
  return ok;
}

/// read_bounded that throws fail(problem)'s exception (fail does not return).
template <class Fail>
std::string read_bounded_or(const std::filesystem::path& path, std::size_t limit, Fail&& fail) {
  std::string text, problem;
  if (!read_bounded(path, limit, text, problem)) fail(problem);
  return text;
}

/// "line is longer than the limit of 65536 bytes (64 KiB) (it starts \"t_s,i_A…\")"
inline std::string long_line_problem(std::string_view start, std::size_t limit = kMaxLineBytes) {
  return "the line is longer than the limit of " + bytes_text(limit) + " (it starts " +
         quoted(start) + ")";
}

}  // namespace palp::format
