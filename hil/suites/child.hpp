// SPDX-License-Identifier: Apache-2.0
// Child processes of the suites: the palp-sim or QEMU they run against, and the host-loss
// scenario's doomed host. Each child dies with the suites (PR_SET_PDEATHSIG: SIGKILL), so a
// suite killed by ctest's timeout leaves no QEMU or palp-sim behind.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace palp::hil {

class Child {
 public:
  /// Starts argv[0] (a path, or a name looked up in PATH) with these arguments; its stdout is read
  /// with read_line(), its stderr goes to a file that stderr_text() reads. On failure, running() is
  /// false and error() says why.
  explicit Child(std::vector<std::string> argv);
  ~Child();  ///< stop(): a child is never left behind
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  bool running() const { return pid_ > 0 && !exited_; }
  pid_t pid() const { return pid_; }
  const std::string& error() const { return error_; }
  /// The command line, for messages.
  std::string command() const;

  /// The next line of its stdout (without the newline), waiting at most `patience` (0: only
  /// what the pipe holds already); false when none came (the child closed stdout, or the time
  /// ran out).
  bool read_line(std::string& line, std::chrono::milliseconds patience);
  /// What it wrote on stderr so far (at most the last 4 kB).
  std::string stderr_text() const;
  /// True once it has exited (reaps it); exit_status() then holds waitpid's status.
  bool exited();
  int exit_status() const { return status_; }
  /// Sends a signal.
  void signal(int sig);
  /// SIGTERM, up to 2 s to exit, then SIGKILL; reaps it.
  void stop();

 private:
  std::vector<std::string> argv_;
  pid_t pid_ = -1;
  int out_ = -1;
  std::string stderr_path_, buffered_, error_;
  bool exited_ = false;
  int status_ = 0;
};

/// A loopback TCP port that was free a moment ago (the kernel's pick for port 0). Whoever binds
/// it next may lose a race; callers retry with another.
std::uint16_t free_loopback_port();

}  // namespace palp::hil
