// SPDX-License-Identifier: Apache-2.0
// Child processes of the suites (child.hpp).
#include "child.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

namespace palp::hil {

Child::Child(std::vector<std::string> argv) : argv_(std::move(argv)) {
  char path[] = "/tmp/palp-hil-child-XXXXXX";
  const int err = ::mkstemp(path);
  if (err < 0) {
    error_ = std::string("cannot start ") + command() + ": mkstemp: " + std::strerror(errno);
    return;
  }
  stderr_path_ = path;
  int out[2];
  if (::pipe2(out, O_CLOEXEC) != 0) {
    error_ = std::string("cannot start ") + command() + ": pipe: " + std::strerror(errno);
    ::close(err);
    return;
  }
  std::vector<char*> args;
  for (std::string& a : argv_) args.push_back(a.data());
  args.push_back(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive the suites (a ctest timeout kills them)
    if (::getppid() != parent) std::_Exit(126);  // the parent died before prctl took hold
    ::dup2(out[1], STDOUT_FILENO);
    ::dup2(err, STDERR_FILENO);
    const int null = ::open("/dev/null", O_RDONLY);
    if (null >= 0) ::dup2(null, STDIN_FILENO);
    ::execvp(args[0], args.data());  // a bare name (qemu-system-arm) is looked up in PATH
    std::fprintf(stderr, "exec %s: %s\n", args[0], std::strerror(errno));
    std::_Exit(127);
  }
  ::close(out[1]);
  ::close(err);
  if (pid < 0) {
    ::close(out[0]);
    error_ = std::string("cannot start ") + command() + ": fork: " + std::strerror(errno);
    return;
  }
  pid_ = pid;
  out_ = out[0];
}

Child::~Child() {
  stop();
  if (out_ >= 0) ::close(out_);
  if (!stderr_path_.empty()) ::unlink(stderr_path_.c_str());
}

std::string Child::command() const {
  std::string c;
  for (const std::string& a : argv_) c += (c.empty() ? "" : " ") + a;
  return c;
}

bool Child::read_line(std::string& line, std::chrono::milliseconds patience) {
  const auto give_up = std::chrono::steady_clock::now() + patience;
  while (true) {
    if (const std::size_t nl = buffered_.find('\n'); nl != std::string::npos) {
      line = buffered_.substr(0, nl);
      buffered_.erase(0, nl + 1);
      return true;
    }
    if (out_ < 0) return false;
    // out of patience: still take what the pipe holds now (poll with 0), never wait
    const auto left = std::max(std::chrono::milliseconds(0),
                               std::chrono::duration_cast<std::chrono::milliseconds>(
                                   give_up - std::chrono::steady_clock::now()));
    pollfd p{out_, POLLIN, 0};
    const int r = ::poll(&p, 1, static_cast<int>(left.count()));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    char buf[512];
    const ssize_t n = ::read(out_, buf, sizeof buf);
    if (n <= 0) {  // stdout closed: the child ended (or closed it)
      ::close(out_);
      out_ = -1;
      continue;
    }
    buffered_.append(buf, static_cast<std::size_t>(n));
  }
}

std::string Child::stderr_text() const {
  std::ifstream in(stderr_path_);
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  if (text.size() > 4096) text = "..." + text.substr(text.size() - 4096);
  return text;
}

bool Child::exited() {
  if (pid_ <= 0 || exited_) return true;
  if (::waitpid(pid_, &status_, WNOHANG) == pid_) exited_ = true;
  return exited_;
}

void Child::signal(int sig) {
  if (running()) ::kill(pid_, sig);
}

void Child::stop() {
  if (!running()) return;
  ::kill(pid_, SIGTERM);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (!exited() && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  if (!exited()) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, &status_, 0);
    exited_ = true;
  }
}

std::uint16_t free_loopback_port() {
  const int s = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (s < 0) return 0;
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  socklen_t len = sizeof a;
  std::uint16_t port = 0;
  if (::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
      ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &len) == 0)
    port = ntohs(a.sin_port);
  ::close(s);
  return port;
}

}  // namespace palp::hil
