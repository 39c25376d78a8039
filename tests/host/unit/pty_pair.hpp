// SPDX-License-Identifier: Apache-2.0
// A pseudo-terminal pair for serial:// tests: the slave is the tty the transport opens by name
// (serial:// + slave_name()), the master is the far end (the "board"). The slave is also held
// open here, as openpty() does, so the master never reads EIO before the transport opens it.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace palp::test {

class PtyPair {
 public:
  PtyPair() {
    master_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    char name[128] = {};
    if (master_ < 0 || ::grantpt(master_) != 0 || ::unlockpt(master_) != 0 ||
        ::ptsname_r(master_, name, sizeof name) != 0)
      return;
    slave_name_ = name;
    slave_ = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
  }
  ~PtyPair() {
    close_master();
    if (slave_ >= 0) ::close(slave_);
  }
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;

  bool ok() const { return master_ >= 0 && slave_ >= 0; }
  const std::string& slave_name() const { return slave_name_; }
  std::string uri() const { return "serial://" + slave_name_; }
  int master() const { return master_; }
  /// The far end goes away (a USB-serial adapter unplugged, a board's link closed).
  void close_master() {
    if (master_ >= 0) ::close(master_);
    master_ = -1;
  }

  /// Everything the master reads until `quiet` passes with nothing more.
  std::vector<std::uint8_t> read_master(std::chrono::milliseconds quiet) {
    std::vector<std::uint8_t> got;
    pollfd p{master_, POLLIN, 0};
    while (::poll(&p, 1, static_cast<int>(quiet.count())) == 1) {
      std::uint8_t b[512];
      const ssize_t n = ::read(master_, b, sizeof b);
      if (n <= 0) break;
      got.insert(got.end(), b, b + n);
    }
    return got;
  }
  bool write_master(const std::vector<std::uint8_t>& bytes) {
    return ::write(master_, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size());
  }

 private:
  int master_ = -1;
  int slave_ = -1;
  std::string slave_name_;
};

}  // namespace palp::test
