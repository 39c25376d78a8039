// SPDX-License-Identifier: Apache-2.0
// Starts palp-sim as a child process on ephemeral loopback ports and talks to it over real
// sockets: the device protocol on one, the control channel on the other.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "palp/protocol/frame.hpp"
#include "palp/protocol/schema.hpp"
#include "palp/protocol/stream.hpp"
#include "loopback.hpp"
#include "sanitized.hpp"

namespace palp::sim::test {

class SimProcess {
 public:
  /// connect_device true connects to the device socket and opens a session (hello());
  /// connect_device false leaves the device socket to another client (palp-sim serves one):
  /// the SDK under test. port 0 lets palp-sim pick one; a restart passes the previous port.
  explicit SimProcess(std::vector<std::string> extra_args = {}, bool connect_device = true,
                      std::uint16_t port = 0) {
    int out[2];
    if (::pipe(out) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(out[1], 1);
      ::close(out[0]);
      std::vector<std::string> args = {PALP_SIM_BINARY, "--port", std::to_string(port),
                                       "--control-port", "0", "--pace", "fast"};
      args.insert(args.end(), extra_args.begin(), extra_args.end());
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      std::_Exit(127);
    }
    ::close(out[1]);
    // "palp-sim listening on tcp://127.0.0.1:P (device protocol), control on tcp://127.0.0.1:C"
    // and, with --robot-port, ", robot bridge on tcp://127.0.0.1:R"
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
    const std::size_t robot = line.find("robot bridge on tcp://127.0.0.1:");
    if (robot != std::string::npos)
      robot_port_ = static_cast<std::uint16_t>(std::stoul(line.substr(robot + 32)));
    unsigned dp = 0, cp = 0;
    if (std::sscanf(line.c_str(), "palp-sim listening on tcp://127.0.0.1:%u (device protocol), "
                                  "control on tcp://127.0.0.1:%u", &dp, &cp) == 2) {
      device_port_ = static_cast<std::uint16_t>(dp);
      if (connect_device) {
        device_ = connect_to(device_port_);
        hello();
      }
      control_ = connect_to(static_cast<std::uint16_t>(cp));
      connect_device_ = connect_device;
    }
  }
  ~SimProcess() {
    if (device_ >= 0) ::close(device_);
    if (control_ >= 0) ::close(control_);
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      int status = 0;
      ::waitpid(pid_, &status, 0);
    }
  }
  bool ok() const { return (device_ >= 0 || !connect_device_) && control_ >= 0; }
  std::uint16_t device_port() const { return device_port_; }
  /// The SDK URI of the device socket.
  std::string uri() const { return "sim://127.0.0.1:" + std::to_string(device_port_); }
  /// The robot bridge's Modbus TCP port (0 when palp-sim runs without --robot-port).
  std::uint16_t robot_port() const { return robot_port_; }
  /// The SDK URI of the robot bridge.
  std::string robot_uri() const { return "modbus://127.0.0.1:" + std::to_string(robot_port_); }
  /// Stops palp-sim now (SIGTERM) and waits for it.
  void stop() {
    if (control_ >= 0) ::close(control_);
    control_ = -1;
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
      pid_ = -1;
    }
  }
  const std::string& banner() const { return banner_; }
  pid_t pid() const { return pid_; }
  /// Connects the device socket now (left to another client at construction, now gone).
  bool connect_device_now() {
    if (device_ < 0) device_ = connect_to(device_port_);
    return device_ >= 0;
  }
  /// The control channel's socket, for tests that write it raw.
  int control_fd() const { return control_; }
  bool alive() const { return pid_ > 0 && ::waitpid(pid_, nullptr, WNOHANG) == 0; }

  void send_bytes(const std::vector<proto::u8>& bytes) {
    std::size_t off = 0;
    while (off < bytes.size()) {
      const ssize_t n = ::write(device_, bytes.data() + off, bytes.size() - off);
      if (n <= 0) return;
      off += static_cast<std::size_t>(n);
    }
  }
  /// Closes the device socket, waits until palp-sim has let the client go, and connects again
  /// without a Hello (a new client: a new session, SPEC.md §6.2). False when it cannot.
  bool reconnect_without_hello() {
    if (device_ >= 0) ::close(device_);
    device_ = -1;
    for (int k = 0; k < 500 && control("status").find(" client=0 ") == std::string::npos; ++k)
      ::usleep(10'000);
    device_ = connect_to(device_port_);
    return device_ >= 0;
  }
  /// Opens a session on the device socket (Hello, seq 0; the constructor does it when it
  /// connects): palp-sim serves nothing but identify and bootloader before it.
  void hello() {
    send(proto::Hello{proto::kProtocolMajor, proto::kProtocolMinor, proto::kSchemaHash, "test"}, 0);
  }
  template <class M>
  void send(const M& m, proto::u16 seq) {
    std::vector<proto::u8> w(proto::kMaxWireFrame);
    w.resize(proto::encode_message(m, seq, 0, w.data(), w.size()));
    send_bytes(w);
  }

  /// Reads device frames until one of type M with the response flag and this seq arrives (or
  /// timeout_ms of wall time); returns whether it did, with its value.
  template <class M>
  bool await(proto::u16 seq, M& out, int timeout_ms = 5000) {
    return await_collecting(seq, out, [](const auto&) {}, timeout_ms);
  }

  /// As await(), handing every other message that arrives meanwhile to seen(m).
  template <class M, class Seen>
  bool await_collecting(proto::u16 seq, M& out, Seen&& seen, int timeout_ms = 5000) {
    bool found = false;
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (!found && std::chrono::steady_clock::now() < end) {
      pollfd p{device_, POLLIN, 0};
      if (::poll(&p, 1, 50) != 1) continue;
      proto::u8 buf[4096];
      const ssize_t n = ::read(device_, buf, sizeof buf);
      if (n <= 0) return false;
      reader_.feed_messages(
          buf, static_cast<std::size_t>(n),
          [&](const proto::FrameHeader& h, const auto& m) {
            if constexpr (std::is_same_v<std::decay_t<decltype(m)>, M>) {
              if (!found && h.seq == seq && (h.flags & proto::kFlagResponse)) {
                out = m;
                found = true;
                return;
              }
            }
            seen(m);
          },
          [](proto::Reject) {});
    }
    return found;
  }

  std::string control(const std::string& line) {
    const std::string l = line + "\n";
    if (::write(control_, l.data(), l.size()) != static_cast<ssize_t>(l.size())) return "";
    std::string reply;
    pollfd p{control_, POLLIN, 0};
    while (reply.find('\n') == std::string::npos && ::poll(&p, 1, 5000) == 1) {
      char c[512];
      const ssize_t n = ::read(control_, c, sizeof c);
      if (n <= 0) break;
      reply.append(c, static_cast<std::size_t>(n));
    }
    if (!reply.empty() && reply.back() == '\n') reply.pop_back();
    return reply;
  }

 private:
  static int connect_to(std::uint16_t port) { return connect_loopback(port); }

  pid_t pid_ = -1;
  std::uint16_t device_port_ = 0;
  std::uint16_t robot_port_ = 0;
  bool connect_device_ = true;
  int device_ = -1;
  int control_ = -1;
  std::string banner_;
  proto::FrameReader reader_;
};

}  // namespace palp::sim::test
