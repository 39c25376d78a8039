// SPDX-License-Identifier: Apache-2.0
// palp-sim as a process against a flooding peer (issue 17, item 5): 200 MB on the control
// channel with no newline leaves its resident memory bounded, and the channel answers after.
#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include "sanitized.hpp"
#include "sim_process.hpp"

namespace palp::sim::test {
namespace {

/// A field of /proc/<pid>/status in kB (VmHWM: peak resident memory, VmRSS: now).
long proc_status_kB(pid_t pid, const std::string& field) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(field + ":", 0) == 0) return std::stol(line.substr(field.size() + 1));
  return -1;
}

TEST(PalpSimLimits, TwoHundredMegabytesWithoutANewlineLeaveItsMemoryBoundedAndItAnswersAfter) {
  if (kSanitized)  // ASan's quarantine keeps up to 256 MB of freed receive buffers resident
    GTEST_SKIP() << "peak memory is measured in the release build";
  SimProcess sim;
  ASSERT_TRUE(sim.ok()) << sim.banner();
  ASSERT_EQ(sim.control("status").rfind("ok ", 0), 0u);
  const long hwm0_kB = proc_status_kB(sim.pid(), "VmHWM");
  ASSERT_GT(hwm0_kB, 0);
  const std::vector<char> chunk(1 << 20, 'x');
  const int fd = sim.control_fd();
  for (int mb = 0; mb < 200; ++mb) {
    std::size_t off = 0;
    while (off < chunk.size()) {
      const ssize_t n = ::write(fd, chunk.data() + off, chunk.size() - off);
      ASSERT_GT(n, 0) << "palp-sim stopped reading after " << mb << " MB";
      off += static_cast<std::size_t>(n);
    }
  }
  // its newline ends the discarded line: one error for it, then the next command is answered
  ASSERT_EQ(::write(fd, "\nstatus\n", 8), 8);
  std::string replies;
  pollfd p{fd, POLLIN, 0};
  while (std::count(replies.begin(), replies.end(), '\n') < 2 && ::poll(&p, 1, 10000) == 1) {
    char c[4096];
    const ssize_t n = ::read(fd, c, sizeof c);
    if (n <= 0) break;
    replies.append(c, static_cast<std::size_t>(n));
  }
  EXPECT_EQ(replies.rfind("error: line longer than 4096 bytes: discarded up to its newline\nok virtual_s=", 0), 0u)
      << replies.substr(0, 200);
  const long hwm_kB = proc_status_kB(sim.pid(), "VmHWM");
  std::printf("palp-sim VmHWM %ld kB before, %ld kB after 200 MB without a newline\n", hwm0_kB, hwm_kB);
  EXPECT_LT(hwm_kB - hwm0_kB, 16 * 1024);  // it was 200+ MB: the whole line was kept
}

}  // namespace
}  // namespace palp::sim::test
