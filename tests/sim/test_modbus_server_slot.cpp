// SPDX-License-Identifier: Apache-2.0
// palp-sim's Modbus server's one client slot (issue 17, item 6), driven directly with a handler
// that answers every read, over real loopback sockets: the second client told who holds the
// slot, a partial request and a silent client timed out, a client that polls kept.
#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "palp/sim/modbus_server.hpp"
#include "loopback.hpp"

namespace palp::sim {
namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

struct Answering : ModbusHandler {
  ModbusException read(std::uint16_t, std::uint16_t count, std::uint16_t* out) override {
    for (std::uint16_t k = 0; k < count; ++k) out[k] = k;
    return ModbusException::none;
  }
  ModbusException write(std::uint16_t, std::span<const std::uint16_t>, bool) override {
    return ModbusException::none;
  }
  void closed() override { ++closes; }
  int closes = 0;
};

struct Slot {
  ModbusServer server{"127.0.0.1", 0};
  Answering handler;
  Clock::time_point t0 = Clock::now();
  std::uint64_t wall_us() const {
    return static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - t0).count()) + 1;
  }
  /// Polls for this long of wall time.
  void poll_for(std::chrono::milliseconds d) {
    const auto end = Clock::now() + d;
    while (Clock::now() < end) {
      server.poll(handler, wall_us());
      std::this_thread::sleep_for(1ms);
    }
  }
};

/// What the peer sent before closing (or within 1 s); closed: it did close.
std::string read_until_closed(int fd, bool& closed) {
  std::string got;
  closed = false;
  pollfd p{fd, POLLIN, 0};
  const auto end = Clock::now() + 1s;
  while (Clock::now() < end && ::poll(&p, 1, 50) >= 0) {
    if (!(p.revents & (POLLIN | POLLHUP))) continue;
    char buf[512];
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) {
      closed = true;
      break;
    }
    got.append(buf, static_cast<std::size_t>(n));
  }
  return got;
}

// FC3 read of 2 registers at 0, transaction id t
std::string read_request(std::uint8_t t) {
  return std::string{'\0', static_cast<char>(t), '\0', '\0', '\0', '\6', '\1', '\3', '\0', '\0', '\0', '\2'};
}

TEST(ModbusServerSlot, ASecondClientIsToldWhoHoldsTheSlotAndSince) {
  Slot s;
  const int first = test::connect_loopback(s.server.port());
  s.poll_for(20ms);
  ASSERT_TRUE(s.server.has_client());
  const int second = test::connect_loopback(s.server.port());
  s.poll_for(20ms);
  bool closed = false;
  const std::string said = read_until_closed(second, closed);
  EXPECT_TRUE(closed);
  EXPECT_EQ(said.rfind("palp-sim: busy: another host is connected from 127.0.0.1:", 0), 0u) << said;
  EXPECT_NE(said.find(" since 20"), std::string::npos) << said;
  EXPECT_TRUE(s.server.has_client());  // the first keeps it
  ::close(second);
  ::close(first);
}

TEST(ModbusServerSlot, APartialRequestLosesTheSlotAfterThePartialTimeAndAPollingClientKeepsIt) {
  Slot s;
  s.server.set_timeouts_ms(400, 150);
  const int polling = test::connect_loopback(s.server.port());
  s.poll_for(10ms);
  ASSERT_TRUE(s.server.has_client());
  for (int k = 0; k < 8; ++k) {  // a whole request every 100 ms for 0.8 s: beyond both times
    const std::string r = read_request(static_cast<std::uint8_t>(k));
    ASSERT_EQ(::write(polling, r.data(), r.size()), static_cast<ssize_t>(r.size()));
    s.poll_for(100ms);
  }
  EXPECT_TRUE(s.server.has_client());
  EXPECT_EQ(s.server.counters().timeouts, 0u);
  const std::string half = read_request(9).substr(0, 5);  // then half a request, and nothing
  ASSERT_EQ(::write(polling, half.data(), half.size()), 5);
  s.poll_for(100ms);
  EXPECT_TRUE(s.server.has_client());
  s.poll_for(150ms);
  EXPECT_FALSE(s.server.has_client());
  EXPECT_EQ(s.server.counters().timeouts, 1u);
  EXPECT_EQ(s.handler.closes, 1);
  ::close(polling);
}

TEST(ModbusServerSlot, ASilentClientLosesTheSlotAfterTheIdleTime) {
  Slot s;
  s.server.set_timeouts_ms(300, 150);
  const int silent = test::connect_loopback(s.server.port());
  s.poll_for(200ms);
  EXPECT_TRUE(s.server.has_client());
  s.poll_for(200ms);
  EXPECT_FALSE(s.server.has_client());
  EXPECT_EQ(s.server.counters().timeouts, 1u);
  const int next = test::connect_loopback(s.server.port());  // the slot is free again
  s.poll_for(20ms);
  EXPECT_TRUE(s.server.has_client());
  EXPECT_EQ(s.server.counters().refused, 0u);
  ::close(next);
  ::close(silent);
}

}  // namespace
}  // namespace palp::sim
