// SPDX-License-Identifier: Apache-2.0
// RecordingWriter: rows into a hidden temporary CSV through a 1 MiB buffer, the sidecar into a
// temporary JSON, both fsync'ed, then renamed sidecar first and CSV last (the CSV's rename is the
// commit point; recording.hpp explains why this order).
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <system_error>

#include "palp/error.hpp"
#include "palp/recording.hpp"
#include "recording/internal.hpp"

#ifndef PALP_SDK_VERSION
#define PALP_SDK_VERSION "unknown"
#endif

namespace palp {
namespace rd = recording_detail;
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kBufferBytes = 1u << 20;

std::string errno_text() { return std::strerror(errno); }

/// Opens a new, hidden file beside `final_path` that nobody else has (O_EXCL).
std::FILE* create_temporary(const fs::path& final_path, fs::path& temporary) {
  for (int attempt = 0; attempt < 1000; ++attempt) {
    temporary = rd::temporary_sibling(final_path);
    if (std::FILE* f = std::fopen(temporary.c_str(), "wbx")) return f;
    if (errno != EEXIST)
      throw RecordingError(final_path.string(), 0,
                           "cannot create " + temporary.string() + ": " + errno_text());
  }
  throw RecordingError(final_path.string(), 0, "cannot find a free temporary name beside it");
}

/// Flushes stdio and the kernel's cache to the disk, then closes; false (errno set) on failure.
bool sync_and_close(std::FILE* f) {
  const bool synced = std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
  const int saved = errno;
  const bool closed = std::fclose(f) == 0;
  if (!synced) errno = saved;
  return synced && closed;
}

char* put(char* p, double v) { return std::to_chars(p, p + rd::kNumberChars, v).ptr; }
template <class Int>
char* put_int(char* p, Int v) {
  return std::to_chars(p, p + rd::kNumberChars, v).ptr;
}

}  // namespace

fs::path rd::temporary_sibling(const fs::path& final_path) {
  static std::atomic<unsigned> counter{0};
  return final_path.parent_path() / ("." + final_path.filename().string() + ".tmp-" +
                                     std::to_string(::getpid()) + "-" +
                                     std::to_string(counter.fetch_add(1)));
}

void rd::sync_directory(const fs::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;  // best effort: the renames are done either way
  (void)::fsync(fd);
  ::close(fd);
}

std::string rd::utc_now() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

struct RecordingWriter::Impl {
  fs::path csv_final, json_final, csv_temporary, json_temporary;
  WriterOptions options;
  std::FILE* csv = nullptr;  ///< open until finish() closes it
  std::string buffer;
  std::uint32_t crc_state = rd::Crc32::kInit;
  std::uint64_t rows = 0;
  double last_t_s = 0;
  bool finished = false;

  ~Impl() { discard(); }

  void discard() noexcept {
    if (csv != nullptr) std::fclose(csv);
    csv = nullptr;
    if (finished) return;
    std::error_code ignored;
    if (!csv_temporary.empty()) fs::remove(csv_temporary, ignored);
    if (!json_temporary.empty()) fs::remove(json_temporary, ignored);
  }

  void write_out() {
    crc_state = rd::Crc32::update(crc_state, buffer.data(), buffer.size());
    if (std::fwrite(buffer.data(), 1, buffer.size(), csv) != buffer.size())
      throw RecordingError(csv_final.string(), 0, "cannot write: " + errno_text());
    buffer.clear();
  }

  void refuse_existing() const {
    for (const fs::path& p : {csv_final, json_final})
      if (fs::exists(p))
        throw ConfigError(p.string() +
                          " already exists; choose another name, or pass "
                          "WriterOptions{.overwrite = palp::Overwrite::yes} to replace it");
  }

  [[noreturn]] void bad_value(std::string_view column, double v) const {
    throw ConfigError(csv_final.string() + ": row " + std::to_string(rows) + ": " +
                      std::string(column) + " is " + rd::shortest(v) +
                      "; a recording holds finite numbers only");
  }

  void check(const RecordingRow& row) const {
    const ColumnSet& c = options.columns;
    if (!std::isfinite(row.t_s)) bad_value("t_s", row.t_s);
    if (!std::isfinite(row.i_A)) bad_value("i_A", row.i_A);
    if (!std::isfinite(row.z_mm)) bad_value("z_mm", row.z_mm);
    if (c.has(Column::i_cmd_A) && !std::isfinite(row.i_cmd_A)) bad_value("i_cmd_A", row.i_cmd_A);
    for (std::size_t k = 0; k < row.p_Pa.size(); ++k)
      if (c.has(pressure_column(k)) && !std::isfinite(row.p_Pa[k]))
        bad_value(column_name(pressure_column(k)), row.p_Pa[k]);
    if (rows > 0 && row.t_s < last_t_s)
      throw ConfigError(csv_final.string() + ": row " + std::to_string(rows) + ": t_s " +
                        rd::shortest(row.t_s) + " is below the previous row's " +
                        rd::shortest(last_t_s) + "; t_s must not decrease");
  }

  void format(const RecordingRow& row) {
    char line[kColumnCount * (rd::kNumberChars + 1) + 1];
    char* p = line;
    const ColumnSet& c = options.columns;
    for (std::size_t k = 0; k < kColumnCount; ++k) {
      const auto col = static_cast<Column>(k);
      if (!c.has(col)) continue;
      if (p != line) *p++ = ',';
      switch (col) {
        case Column::sample_index: p = put_int(p, row.sample_index); break;
        case Column::t_s: p = put(p, row.t_s); break;
        case Column::i_cmd_A: p = put(p, row.i_cmd_A); break;
        case Column::i_A: p = put(p, row.i_A); break;
        case Column::z_mm: p = put(p, row.z_mm); break;
        case Column::status: p = put_int(p, row.status); break;
        case Column::rep: p = put_int(p, row.rep); break;
        default: p = put(p, row.p_Pa[k - static_cast<std::size_t>(Column::p1_Pa)]); break;
      }
    }
    *p++ = '\n';
    buffer.append(line, p);
  }
};

RecordingWriter::RecordingWriter(const fs::path& csv_or_stem, WriterOptions options)
    : impl_(std::make_unique<Impl>()) {
  Impl& w = *impl_;
  w.csv_final = recording_csv_path(csv_or_stem);
  w.json_final = recording_sidecar_path(w.csv_final);
  w.options = options;
  if (options.overwrite == Overwrite::no) w.refuse_existing();
  w.csv = create_temporary(w.csv_final, w.csv_temporary);
  w.buffer.reserve(kBufferBytes + 1024);
  for (std::size_t k = 0; k < kColumnCount; ++k) {
    if (!options.columns.has(static_cast<Column>(k))) continue;
    if (!w.buffer.empty()) w.buffer += ',';
    w.buffer += kColumnNames[k];
  }
  w.buffer += '\n';
}

RecordingWriter::~RecordingWriter() = default;
RecordingWriter::RecordingWriter(RecordingWriter&&) noexcept = default;
RecordingWriter& RecordingWriter::operator=(RecordingWriter&&) noexcept = default;

void RecordingWriter::append(const RecordingRow& row) {
  Impl& w = *impl_;
  if (w.csv == nullptr)
    throw ConfigError(w.csv_final.string() + ": append() after finish(); the recording is closed");
  w.check(row);
  w.format(row);
  w.last_t_s = row.t_s;
  ++w.rows;
  if (w.buffer.size() >= kBufferBytes) w.write_out();
}

Sidecar RecordingWriter::finish(const Sidecar& sidecar) {
  Impl& w = *impl_;
  const std::string csv_name = w.csv_final.string();
  if (w.csv == nullptr) throw ConfigError(csv_name + ": finish() was called already");
  if (w.rows == 0)
    throw ConfigError(csv_name + ": no row was appended; a recording needs at least one");
  Sidecar s = sidecar;
  if (s.sdk_version.empty()) s.sdk_version = PALP_SDK_VERSION;
  if (s.created_utc.empty()) s.created_utc = rd::utc_now();
  s.csv_rows = w.rows;
  s.csv_crc32 = 0;
  (void)rd::sidecar_document(s);  // refuses a bad sidecar before anything is closed or renamed
  if (w.options.overwrite == Overwrite::no) w.refuse_existing();

  w.write_out();
  std::FILE* csv = w.csv;
  w.csv = nullptr;
  if (!sync_and_close(csv)) throw RecordingError(csv_name, 0, "cannot write: " + errno_text());
  s.csv_crc32 = rd::Crc32::final(w.crc_state);

  const std::string text =
      rd::sidecar_document(s).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  std::FILE* sidecar_file = create_temporary(w.json_final, w.json_temporary);
  const bool written = std::fwrite(text.data(), 1, text.size(), sidecar_file) == text.size();
  if (!sync_and_close(sidecar_file) || !written)
    throw RecordingError(w.json_final.string(), 0, "cannot write: " + errno_text());

  std::error_code ec;
  fs::rename(w.json_temporary, w.json_final, ec);
  if (ec)
    throw RecordingError(w.json_final.string(), 0,
                         "cannot rename the finished sidecar into place: " + ec.message());
  fs::rename(w.csv_temporary, w.csv_final, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(w.json_final, ignored);  // no sidecar without its CSV
    throw RecordingError(csv_name, 0, "cannot rename the finished CSV into place: " + ec.message());
  }
  w.finished = true;
  rd::sync_directory(w.csv_final.parent_path());
  return s;
}

std::uint64_t RecordingWriter::rows() const { return impl_->rows; }
bool RecordingWriter::finished() const { return impl_->finished; }
const fs::path& RecordingWriter::csv_path() const { return impl_->csv_final; }
const fs::path& RecordingWriter::sidecar_path() const { return impl_->json_final; }

}  // namespace palp
