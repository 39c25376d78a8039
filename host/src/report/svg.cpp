// SPDX-License-Identifier: Apache-2.0
// The report's figures as standalone SVG files: every spec is written to a temporary directory
// and host/report/vega-to-svg.js renders them all in one node process (Debian's node-vega, no
// browser) into the SVG directory, which is written as a result directory is (result_dir.hpp).
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "experiments/result_dir.hpp"
#include "palp/error.hpp"
#include "palp/report.hpp"

extern char** environ;

namespace palp::report {

namespace fs = std::filesystem;

namespace {

/// vega-to-svg.js's exit code when node-vega's modules cannot be loaded.
constexpr int kScriptMissingVega = 3;
/// The longest message kept from the script's stderr.
constexpr std::size_t kMaxMessageBytes = 4000;

std::optional<fs::path> on_path(const char* name) {
  const char* path = std::getenv("PATH");
  std::string dirs = path != nullptr ? path : "/usr/bin:/bin";
  for (std::size_t b = 0; b <= dirs.size();) {
    const std::size_t e = std::min(dirs.find(':', b), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(b, e - b)) / name;
    if (e > b && ::access(candidate.c_str(), X_OK) == 0) return candidate;
    b = e + 1;
  }
  return std::nullopt;
}

fs::path node_program() {
  if (const char* env = std::getenv("PALP_NODE"); env != nullptr && *env != '\0') return env;
  for (const char* name : {"node", "nodejs"})
    if (auto p = on_path(name)) return *p;
  throw ConfigError("SVG figures need node (Debian's nodejs) on PATH, or PALP_NODE naming it; install nodejs and "
                    "node-vega (scripts/install-deps)");
}

/// The script: $PALP_VEGA_TO_SVG, else share/palp/ of the running program's installation
/// (<prefix>/bin/palpctl -> <prefix>/share/palp/vega-to-svg.js), else this source tree's.
fs::path script_path() {
  if (const char* env = std::getenv("PALP_VEGA_TO_SVG"); env != nullptr && *env != '\0') return env;
  std::vector<fs::path> tried;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) tried.push_back(exe.parent_path().parent_path() / "share" / "palp" / "vega-to-svg.js");
#ifdef PALP_SOURCE_DIR
  tried.push_back(fs::path(PALP_SOURCE_DIR) / "host" / "report" / "vega-to-svg.js");
#endif
  std::string names;
  for (const fs::path& p : tried) {
    if (fs::is_regular_file(p, ec)) return p;
    names += (names.empty() ? "" : ", ") + p.string();
  }
  throw ConfigError("vega-to-svg.js (palp's SVG renderer) is not at " + names +
                    "; install palp, or set PALP_VEGA_TO_SVG to the script");
}

/// Runs argv, returning its exit status (-1: it could not start) and its stderr (cut).
int run(const std::vector<std::string>& argv, std::string& err) {
  int pipefd[2];
  if (::pipe2(pipefd, O_CLOEXEC) != 0) throw RecordingError(argv[0], 0, std::string("pipe: ") + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipefd[1], 2);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = ::posix_spawn(&pid, argv[0].c_str(), &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipefd[1]);
  if (rc != 0) {
    ::close(pipefd[0]);
    err = std::strerror(rc);
    return -1;
  }
  std::array<char, 4096> buf{};
  for (;;) {
    const ssize_t got = ::read(pipefd[0], buf.data(), buf.size());
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    if (err.size() < kMaxMessageBytes) err.append(buf.data(), static_cast<std::size_t>(got));
  }
  ::close(pipefd[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// A fresh directory for the specs under the system's temporary directory, removed at scope end.
struct SpecDir {
  fs::path path;
  SpecDir() {
    static std::atomic<unsigned> counter{0};
    path = fs::temp_directory_path() /
           ("palp-report-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    fs::create_directories(path);
  }
  ~SpecDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  SpecDir(const SpecDir&) = delete;
  SpecDir& operator=(const SpecDir&) = delete;
};

}  // namespace

std::vector<fs::path> write_report_svgs(const fs::path& dir_in, const Report& report, Overwrite overwrite) {
  const fs::path dir = prepare_result_directory(dir_in, overwrite, "write_report_svgs");
  std::vector<const Figure*> figures;
  for (const Section& s : report.sections)
    for (const Figure& f : s.figures) figures.push_back(&f);
  for (const Figure* f : figures)
    if (f->id.empty() || f->id.find_first_of("/\\") != std::string::npos || f->id[0] == '.')
      throw ConfigError("write_report_svgs: the figure id \"" + f->id + "\" cannot name a file");
  const fs::path node = node_program();
  const fs::path script = script_path();
  std::vector<fs::path> written;
  SpecDir specs;
  write_result_directory(dir, overwrite, [&](const fs::path& tmp) {
    std::vector<std::string> argv{node.string(), script.string()};
    for (const Figure* f : figures) {
      const fs::path spec = specs.path / (f->id + ".vg.json");
      write_text_file(spec, f->spec.dump());
      argv.push_back(spec.string());
      argv.push_back((tmp / (f->id + ".svg")).string());
    }
    if (figures.empty()) return;
    std::string err;
    const int rc = run(argv, err);
    if (rc == -1) throw ConfigError(node.string() + ": cannot run: " + err + " (install Debian's nodejs)");
    if (rc == kScriptMissingVega) throw ConfigError(err + " (install Debian's node-vega: scripts/install-deps)");
    // the script's own line names the spec and Vega's message; Vega's log before it is noise
    if (const std::size_t at = err.rfind("vega-to-svg: "); at != std::string::npos) err.erase(0, at);
    if (rc != 0)
      throw RecordingError(dir.string(), 0,
                           "the SVG renderer " + script.string() + " failed (exit " + std::to_string(rc) + "): " + err);
  });
  for (const Figure* f : figures) written.push_back(dir / (f->id + ".svg"));
  return written;
}

}  // namespace palp::report
