// SPDX-License-Identifier: Apache-2.0
// Processes for the palpctl tests: palp-sim on ephemeral ports (its banner read, no socket of
// its own opened: palp-sim serves one device client, and that is palpctl) and palpctl itself,
// with its exit code, stdout and stderr.
#pragma once

#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <arpa/inet.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <utility>
#include <cstdio>
#include <string>
#include <vector>

namespace palpctl::test {

/// Runs argv[0] with the arguments; returns when it exits (killed after timeout_s).
struct ProcessResult {
  int code = -1;  ///< exit code; 128 + signal when killed by one
  std::string out, err;
  bool timed_out = false;
  long max_rss_kB = 0;  ///< the process's peak resident set (getrusage of the child, wait4)
};

inline ProcessResult run_process(const std::vector<std::string>& args, double timeout_s = 60) {
  ProcessResult r;
  int out[2], err[2];
  if (::pipe(out) != 0 || ::pipe(err) != 0) return r;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(out[1], 1);
    ::dup2(err[1], 2);
    ::close(out[0]);
    ::close(err[0]);
    ::unsetenv("PALP_URI");
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    std::_Exit(127);
  }
  ::close(out[1]);
  ::close(err[1]);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  pollfd p[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
  int open = 2;
  while (open > 0) {
    if (std::chrono::steady_clock::now() > end) {
      r.timed_out = true;
      ::kill(pid, SIGKILL);
      break;
    }
    if (::poll(p, 2, 100) <= 0) continue;
    for (int k = 0; k < 2; ++k) {
      if (p[k].fd < 0 || (p[k].revents & (POLLIN | POLLHUP)) == 0) continue;
      char buf[4096];
      const ssize_t n = ::read(p[k].fd, buf, sizeof buf);
      if (n <= 0) {
        ::close(p[k].fd);
        p[k].fd = -1;
        --open;
      } else {
        (k == 0 ? r.out : r.err).append(buf, static_cast<std::size_t>(n));
      }
    }
  }
  for (auto& q : p)
    if (q.fd >= 0) ::close(q.fd);
  int status = 0;
  struct rusage usage {};
  ::wait4(pid, &status, 0, &usage);
  r.max_rss_kB = usage.ru_maxrss;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

/// palpctl with these arguments.
inline ProcessResult palpctl(std::vector<std::string> args, double timeout_s = 60) {
  args.insert(args.begin(), PALPCTL_BINARY);
  return run_process(args, timeout_s);
}

/// palp-sim on ephemeral loopback ports, paced as fast as possible.
class SimServer {
 public:
  explicit SimServer(std::vector<std::string> extra = {}) {
    int out[2];
    if (::pipe(out) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(out[1], 1);
      ::close(out[0]);
      std::vector<std::string> args = {PALP_SIM_BINARY, "--port", "0", "--control-port", "0",
                                       "--pace", "fast"};
      args.insert(args.end(), extra.begin(), extra.end());
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      std::_Exit(127);
    }
    ::close(out[1]);
    std::string line;
    pollfd p{out[0], POLLIN, 0};
    while (line.find('\n') == std::string::npos && ::poll(&p, 1, 5000) == 1) {
      char c[256];
      const ssize_t n = ::read(out[0], c, sizeof c);
      if (n <= 0) break;
      line.append(c, static_cast<std::size_t>(n));
    }
    ::close(out[0]);
    banner_ = line;
    unsigned dp = 0, cp = 0;
    if (std::sscanf(line.c_str(),
                    "palp-sim listening on tcp://127.0.0.1:%u (device protocol), "
                    "control on tcp://127.0.0.1:%u",
                    &dp, &cp) == 2) {
      port_ = dp;
      control_port_ = cp;
    }
  }
  ~SimServer() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  SimServer(const SimServer&) = delete;
  SimServer& operator=(const SimServer&) = delete;

  bool ok() const { return port_ != 0; }
  const std::string& banner() const { return banner_; }
  std::string uri() const { return "sim://127.0.0.1:" + std::to_string(port_); }
  /// The robot bridge's port (started with --robot-port), from the banner's
  /// ", robot bridge on tcp://127.0.0.1:R"; 0 without one.
  unsigned robot_port() const {
    const auto at = banner_.find("robot bridge on tcp://127.0.0.1:");
    return at == std::string::npos ? 0u : static_cast<unsigned>(std::stoul(banner_.substr(at + 32)));
  }

  /// One line on palp-sim's control channel (its own knobs; not the device socket); the reply.
  /// Waits until palp-sim has seen its device client go (its control "status" says client=0).
  /// palp-sim refuses a new client while it still holds the old one, so a test that runs palpctl
  /// twice against one simulator waits here in between.
  bool wait_no_client(double timeout_s = 5) const {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < end) {
      if (control("status").find(" client=0 ") != std::string::npos) return true;
      ::usleep(5000);
    }
    return false;
  }

  std::string control(const std::string& line) const {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(control_port_));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    std::string reply;
    if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0) {
      const std::string l = line + "\n";
      if (::write(fd, l.data(), l.size()) == static_cast<ssize_t>(l.size())) {
        pollfd p{fd, POLLIN, 0};
        while (reply.find('\n') == std::string::npos && ::poll(&p, 1, 5000) == 1) {
          char c[512];
          const ssize_t n = ::read(fd, c, sizeof c);
          if (n <= 0) break;
          reply.append(c, static_cast<std::size_t>(n));
        }
      }
    }
    ::close(fd);
    return reply;
  }

 private:
  pid_t pid_ = -1;
  unsigned port_ = 0, control_port_ = 0;
  std::string banner_;
};

/// A loopback TCP port nothing listens on (bound, then released).
inline unsigned unused_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t n = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n);
  ::close(fd);
  return ntohs(a.sin_port);
}

/// A test with its own palp-sim process and a scratch directory (removed afterwards) named
/// `<prefix>-<pid>-<test name>`; run() calls palpctl against that palp-sim once it is free.
class SimCliTest : public ::testing::Test {
 protected:
  explicit SimCliTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    ASSERT_TRUE(sim_.ok()) << "palp-sim did not start: " << sim_.banner();
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           (prefix_ + "-" + std::to_string(::getpid()) + "-" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  ProcessResult run(std::vector<std::string> args) {
    EXPECT_TRUE(sim_.wait_no_client()) << "palp-sim still holds the previous client";
    args.insert(args.begin(), {"--uri", sim_.uri()});
    return palpctl(args);
  }

  std::string prefix_;
  SimServer sim_;
  std::filesystem::path dir_;
};

}  // namespace palpctl::test
