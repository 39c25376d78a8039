// SPDX-License-Identifier: Apache-2.0
// The atomic result directory (result_dir.hpp).
#include "result_dir.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "palp/error.hpp"
#include "palp/probe.hpp"
#include "palp/result.hpp"
#include "recording/internal.hpp"

namespace palp {

namespace fs = std::filesystem;

namespace {

fs::path sibling(const fs::path& dir, const char* what) {
  static std::atomic<unsigned> counter{0};
  return dir.parent_path() / ("." + dir.filename().string() + "." + what + "-" +
                              std::to_string(::getpid()) + "-" + std::to_string(counter++));
}

void fsync_path(const fs::path& p, bool directory) {
  const int fd = ::open(p.c_str(), (directory ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
  if (fd < 0) return;  // best effort: the rename below is what makes the result visible
  ::fsync(fd);
  ::close(fd);
}

/// The names the manifest in dir lists; nullopt when it has none.
std::optional<std::set<std::string>> manifest_of(const fs::path& dir) {
  std::ifstream in(dir / kManifestFile);
  if (!in) return std::nullopt;
  std::set<std::string> names;
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line.find('/') == std::string::npos && line != "." && line != "..") names.insert(line);
  return names;
}

/// Deletes the files the manifest names, the manifest, and then the directory if nothing else
/// is left in it (anything else stays where it is).
void remove_own_files(const fs::path& dir) {
  std::error_code ec;
  if (const auto names = manifest_of(dir))
    for (const std::string& n : *names) fs::remove(dir / n, ec);
  fs::remove(dir / kManifestFile, ec);
  fs::remove(dir, ec);  // fails, and keeps it, when it is not empty
}

}  // namespace

void check_replaceable(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(dir, ec))) return;
  const std::string tail = ": nothing was replaced; move it away, or choose another directory";
  if (!fs::is_directory(fs::symlink_status(dir, ec)))
    throw ConfigError(dir.string() + " is not a directory palp wrote" + tail);
  const auto names = manifest_of(dir);
  if (!names)
    throw ConfigError(dir.string() + " is not a result directory palp wrote (it has no " + kManifestFile +
                      " listing palp's files)" + tail);
  std::vector<std::string> unknown;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string n = e.path().filename().string();
    if (n != kManifestFile && (!names->count(n) || e.is_directory() || e.is_symlink())) unknown.push_back(n);
  }
  if (ec) throw ConfigError(dir.string() + ": cannot list it (" + ec.message() + ")" + tail);
  if (!unknown.empty()) {
    std::sort(unknown.begin(), unknown.end());
    throw ConfigError((dir / unknown.front()).string() + " was not written by palp, so " + dir.string() +
                      " is not replaced (" + std::to_string(unknown.size()) +
                      " such entr" + (unknown.size() == 1 ? "y" : "ies") +
                      "); move it away, or choose another directory");
  }
}

void write_text_file(const fs::path& p, const std::string& text) {
  const int fd = ::open(p.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw RecordingError(p.string(), 0, std::string("cannot create: ") + std::strerror(errno));
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int e = errno;
      ::close(fd);
      throw RecordingError(p.string(), 0, std::string("cannot write: ") + std::strerror(e));
    }
    done += static_cast<std::size_t>(n);
  }
  const bool synced = ::fsync(fd) == 0;
  const int e = errno;
  ::close(fd);
  if (!synced) throw RecordingError(p.string(), 0, std::string("cannot flush: ") + std::strerror(e));
}

fs::path prepare_result_directory(const fs::path& dir_in, Overwrite overwrite, const char* who) {
  const fs::path dir = fs::absolute(dir_in).lexically_normal();
  if (dir.filename().empty()) throw ConfigError(std::string(who) + ": " + dir_in.string() + " names no directory");
  std::error_code ec;
  fs::create_directories(dir.parent_path(), ec);
  if (ec) throw RecordingError(dir.parent_path().string(), 0, "cannot create: " + ec.message());
  if (fs::exists(dir) && overwrite == Overwrite::no)
    throw ConfigError(dir_in.string() + " already exists; choose another directory, or overwrite it");
  check_replaceable(dir);
  return dir;
}

nlohmann::ordered_json result_head(const char* experiment) {
  return {{"schema", kResultSchema}, {"experiment", experiment}, {"created_utc", recording_detail::utc_now()}, {"sdk_version", sdk_version()}};
}

void write_result_directory(const fs::path& dir, Overwrite overwrite,
                            const std::function<void(const fs::path& tmp)>& fill) {
  std::error_code ec;
  const fs::path tmp = sibling(dir, "tmp");
  try {
    fs::create_directory(tmp);
    fill(tmp);
    std::string manifest;
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(tmp)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    for (const std::string& n : names) manifest += n + "\n";
    write_text_file(tmp / kManifestFile, manifest);
    fsync_path(tmp, true);
    if (fs::exists(dir)) {
      if (overwrite == Overwrite::no)
        throw RecordingError(dir.string(), 0, "appeared while the result was written; not replaced");
      check_replaceable(dir);  // again: a file may have been added since the writer checked
      const fs::path old = sibling(dir, "old");
      fs::rename(dir, old);
      fs::rename(tmp, dir);
      remove_own_files(old);
    } else {
      fs::rename(tmp, dir);
    }
    fsync_path(dir.parent_path(), true);
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(tmp, ec);
    throw RecordingError(dir.string(), 0, std::string("cannot write the result: ") + e.code().message());
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
}

void check_own_file_replaceable(const fs::path& file, Overwrite overwrite, const OwnFileKind& kind) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(file, ec);
  if (!fs::exists(st)) return;
  if (overwrite == Overwrite::no)
    throw ConfigError(file.string() + " already exists; choose another file, or overwrite it (palpctl --overwrite)");
  const std::string tail = ": nothing was replaced; move it away, or choose another file";
  if (!fs::is_regular_file(st)) throw ConfigError(file.string() + " " + kind.not_regular + tail);
  std::ifstream in(file, std::ios::binary);
  std::string first(kind.head.size(), '\0');
  in.read(first.data(), static_cast<std::streamsize>(first.size()));
  first.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  if (first != kind.head) throw ConfigError(file.string() + " " + kind.not_ours + tail);
}

void write_own_file(const fs::path& file_in, Overwrite overwrite, const OwnFileKind& kind,
                    const std::function<std::string()>& make_text) {
  const fs::path file = fs::absolute(file_in).lexically_normal();
  if (file.filename().empty()) throw ConfigError(file_in.string() + " names no file");
  check_own_file_replaceable(file, overwrite, kind);
  const std::string text = make_text();
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  if (ec) throw RecordingError(file.parent_path().string(), 0, "cannot create: " + ec.message());
  const fs::path tmp = recording_detail::temporary_sibling(file);
  try {
    write_text_file(tmp, text);
    check_own_file_replaceable(file, overwrite, kind);  // again: it may have appeared meanwhile
    fs::rename(tmp, file);
  } catch (const fs::filesystem_error& e) {
    fs::remove(tmp, ec);
    throw RecordingError(file.string(), 0, "cannot write: " + e.code().message());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  recording_detail::sync_directory(file.parent_path());
}

}  // namespace palp
