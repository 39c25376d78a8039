// SPDX-License-Identifier: Apache-2.0
// serial:// on a pseudo-terminal (no /dev/ttyS* needed): the tty is made raw (every byte value
// passes unchanged both ways, nothing echoed), 8N1 at the baud asked for with no flow control;
// a missing path, a file that is no tty, permission denied and a tty already in use are refused
// with messages that name the path; the far end closing is a ConnectionError at once, not a hang.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <termios.h>

#include <cstdlib>
#include <numeric>
#include <thread>

#include "palp/error.hpp"
#include "palp/transport.hpp"
#include "pty_pair.hpp"

namespace {

using namespace std::chrono_literals;
using palp::test::PtyPair;
using Clock = std::chrono::steady_clock;

std::vector<std::uint8_t> every_byte_value() {
  std::vector<std::uint8_t> v(256);
  std::iota(v.begin(), v.end(), std::uint8_t{0});
  return v;
}

/// Reads from t until n bytes came or 2 s passed.
std::vector<std::uint8_t> read_n(palp::Transport& t, std::size_t n) {
  std::vector<std::uint8_t> got;
  const auto end = Clock::now() + 2s;
  while (got.size() < n && Clock::now() < end) {
    std::uint8_t b[512];
    got.insert(got.end(), b, b + t.read(b, 100ms));
  }
  return got;
}

template <class E>
std::string error_of(const std::string& uri) {
  try {
    palp::open_transport(uri, 500ms);
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("another kind of error: ") + e.what();
  }
  return "opened";
}

TEST(SerialTransport, EveryByteValuePassesUnchangedBothWaysWithNothingEchoed) {
  PtyPair pty;
  ASSERT_TRUE(pty.ok());
  auto t = palp::open_transport(pty.uri(), 500ms);
  const std::vector<std::uint8_t> all = every_byte_value();
  // cooked, the tty would turn \n into \r\n, \r into \n, swallow ^C, ^S and ^D, and echo
  t->write(all, 1s);
  EXPECT_EQ(pty.read_master(200ms), all);
  ASSERT_TRUE(pty.write_master(all));
  EXPECT_EQ(read_n(*t, all.size()), all);
  EXPECT_TRUE(pty.read_master(100ms).empty()) << "the tty echoed what the board sent";
}

TEST(SerialTransport, TheTtyIsSet8N1AtTheBaudAskedForWithNoFlowControl) {
  PtyPair pty;
  ASSERT_TRUE(pty.ok());
  auto t = palp::open_transport(pty.uri() + "?baud=9600", 500ms);
  termios s{};
  const int fd = ::open(pty.slave_name().c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::tcgetattr(fd, &s), 0);
  ::close(fd);
  EXPECT_EQ(::cfgetospeed(&s), B9600);
  EXPECT_EQ(::cfgetispeed(&s), B9600);
  EXPECT_EQ(s.c_cflag & (CSIZE | PARENB | CSTOPB | CRTSCTS | CLOCAL | CREAD), CS8 | CLOCAL | CREAD);
  EXPECT_EQ(s.c_iflag & (IXON | IXOFF | IXANY | ICRNL | ISTRIP), 0u);
  EXPECT_EQ(s.c_lflag & (ICANON | ECHO | ISIG | IEXTEN), 0u);
  EXPECT_EQ(s.c_oflag & OPOST, 0u);
  // 8N1 puts ten bits on the line for each byte
  EXPECT_EQ(t->max_device_bytes_per_s(), 960u);
  EXPECT_EQ(t->uri(), pty.uri() + "?baud=9600");
  EXPECT_EQ(palp::open_transport(PtyPair().uri(), 500ms)->max_device_bytes_per_s(), 11520u)
      << "115200 baud by default";
}

TEST(SerialTransport, AReadWithNothingComingReturnsNothingAfterItsTimeout) {
  PtyPair pty;
  ASSERT_TRUE(pty.ok());
  auto t = palp::open_transport(pty.uri(), 500ms);
  std::uint8_t b[64];
  const auto t0 = Clock::now();
  EXPECT_EQ(t->read(b, 150ms), 0u);
  EXPECT_GE(Clock::now() - t0, 150ms);
}

TEST(SerialTransport, AMissingDeviceIsAConnectionErrorNamingThePath) {
  EXPECT_EQ(error_of<palp::ConnectionError>("serial:///dev/palp-no-such-tty"),
            "serial device /dev/palp-no-such-tty does not exist (is the board plugged in and "
            "powered? `ls /dev/ttyUSB* /dev/ttyACM*` lists the serial devices)");
}

TEST(SerialTransport, ARegularFileIsAConfigErrorSayingItIsNoTerminal) {
  char path[] = "/tmp/palp-not-a-tty-XXXXXX";
  const int fd = ::mkstemp(path);
  ASSERT_GE(fd, 0);
  ::close(fd);
  const std::string uri = std::string("serial://") + path;
  EXPECT_EQ(error_of<palp::ConfigError>(uri),
            "transport URI '" + uri + "': " + path +
                " is not a terminal device: serial:// takes a tty such as /dev/ttyUSB0, "
                "/dev/ttyACM0 or a pty");
  ::unlink(path);
}

TEST(SerialTransport, ATtyAlreadyOpenIsRefusedAsInUseAndKeepsItsSettings) {
  PtyPair pty;
  ASSERT_TRUE(pty.ok());
  auto first = palp::open_transport(pty.uri() + "?baud=9600", 500ms);
  EXPECT_EQ(error_of<palp::ConnectionError>(pty.uri()),
            "serial device " + pty.slave_name() +
                " is in use: another palp host holds its lock (a program using the SDK, or "
                "palpctl); close it first (`fuser " +
                pty.slave_name() + "` names it)");
  termios s{};
  const int fd = ::open(pty.slave_name().c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::tcgetattr(fd, &s), 0);
  ::close(fd);
  EXPECT_EQ(::cfgetospeed(&s), B9600) << "the refused open changed the baud of a tty in use";
  first.reset();  // the lock goes with it
  EXPECT_NO_THROW(palp::open_transport(pty.uri(), 500ms));
}

TEST(SerialTransport, PermissionDeniedSaysToJoinTheDialoutGroup) {
  PtyPair pty;
  ASSERT_TRUE(pty.ok());
  ASSERT_EQ(::chmod(pty.slave_name().c_str(), 0), 0);
  // root may open anything: the attempt runs in a child that is nobody (uid 65534) when root
  int out[2];
  ASSERT_EQ(::pipe(out), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::close(out[0]);
    if (::getuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) std::_Exit(2);
    const std::string e = error_of<palp::ConnectionError>(pty.uri());
    std::_Exit(::write(out[1], e.data(), e.size()) == static_cast<ssize_t>(e.size()) ? 0 : 3);
  }
  ::close(out[1]);
  std::string got;
  pollfd p{out[0], POLLIN, 0};
  while (::poll(&p, 1, 5000) == 1) {
    char b[512];
    const ssize_t n = ::read(out[0], b, sizeof b);
    if (n <= 0) break;
    got.append(b, static_cast<std::size_t>(n));
  }
  ::close(out[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_EQ(got, "permission denied opening serial device " + pty.slave_name() +
                     ": add your user to the dialout group (`sudo usermod -aG dialout $USER`, "
                     "then log in again)");
}

TEST(SerialTransport, TheFarEndClosingWakesAWaitingReadWithAConnectionError) {
  PtyPair pty;
  ASSERT_TRUE(pty.ok());
  auto t = palp::open_transport(pty.uri(), 500ms);
  std::thread unplug([&] {
    std::this_thread::sleep_for(100ms);
    pty.close_master();
  });
  const auto t0 = Clock::now();
  std::string what = "no error";
  try {
    std::uint8_t b[64];
    while (Clock::now() - t0 < 10s) t->read(b, 5s);
  } catch (const palp::ConnectionError& e) {
    what = e.what();
  }
  const auto waited = Clock::now() - t0;
  unplug.join();
  EXPECT_EQ(what, "serial device " + pty.slave_name() +
                      " closed the connection (hung up: unplugged, or its other end closed)");
  EXPECT_LT(waited, 3s) << "the read waited out its 5 s timeout instead of seeing the hang-up";
  EXPECT_THROW(t->write(every_byte_value(), 500ms), palp::ConnectionError);
}

}  // namespace
