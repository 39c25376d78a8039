// SPDX-License-Identifier: Apache-2.0
// serial:///dev/ttyX[?baud=N]: a UART-attached board's tty, opened raw (termios: 8N1, no flow
// control, no echo or line editing, CLOCAL so no modem line is waited for) and locked with
// flock() so two hosts never share one board. Reads and writes are FdTransport's (poll-bounded).
#include <fcntl.h>
#include <sys/file.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "palp/error.hpp"
#include "transport/factories.hpp"
#include "transport/fd_transport.hpp"
#include "transport/serial_speeds.hpp"

namespace palp::detail {
namespace {

/// Why open() refused the tty, and what to do about it.
std::string open_refusal(const std::string& path, int err) {
  switch (err) {
    case ENOENT:
    case ENODEV:
    case ENXIO:
      return "serial device " + path +
             " does not exist (is the board plugged in and powered? "
             "`ls /dev/ttyUSB* /dev/ttyACM*` lists the serial devices)";
    case EACCES:
    case EPERM:
      return "permission denied opening serial device " + path +
             ": add your user to the dialout group (`sudo usermod -aG dialout $USER`, then log "
             "in again)";
    case EBUSY:
      return "serial device " + path + " is busy: another program has it open exclusively";
    default:
      return "cannot open serial device " + path + ": " + std::strerror(err);
  }
}

/// Makes the tty raw at speed: 8 data bits, no parity, 1 stop bit, no flow control, a read
/// wakes for one byte (VMIN 1; the fd is non-blocking and poll() bounds every wait).
void make_raw(int fd, const termios& current, speed_t speed, const std::string& path) {
  termios t = current;
  ::cfmakeraw(&t);
  t.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  t.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS);
  t.c_cflag |= CS8 | CLOCAL | CREAD;
  t.c_cc[VMIN] = 1;
  t.c_cc[VTIME] = 0;
  ::cfsetispeed(&t, speed);
  ::cfsetospeed(&t, speed);
  termios back{};
  if (::tcsetattr(fd, TCSANOW, &t) != 0 || ::tcgetattr(fd, &back) != 0)
    throw ConnectionError("cannot configure serial device " + path + ": " + std::strerror(errno));
  if (::cfgetospeed(&back) != speed)
    throw ConnectionError("serial device " + path +
                          " did not take the baud rate asked for "
                          "(its driver may not support it): choose another with ?baud=N");
  ::tcflush(fd, TCIFLUSH);  // bytes from before this session
}

}  // namespace

std::unique_ptr<Transport> open_serial_transport(const Uri& uri,
                                                 std::chrono::milliseconds /*timeout*/) {
  const std::string& path = uri.path;
  const std::optional<speed_t> speed = termios_speed(uri.baud);
  if (!speed) throw ConfigError("transport URI '" + uri.text + "': " + unsupported_baud(uri.baud));
  // O_NONBLOCK: open() does not wait for a modem's carrier, and reads and writes never block
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw ConnectionError(open_refusal(path, errno));
  const auto fail = [&](auto error) -> std::unique_ptr<Transport> {
    ::close(fd);
    throw error;
  };
  termios current{};
  if (::tcgetattr(fd, &current) != 0) {
    const int err = errno;
    if (err == ENOTTY || err == EINVAL)
      return fail(ConfigError("transport URI '" + uri.text + "': " + path +
                              " is not a terminal device: serial:// takes a tty such as "
                              "/dev/ttyUSB0, /dev/ttyACM0 or a pty"));
    return fail(ConnectionError("cannot read the settings of serial device " + path + ": " +
                                std::strerror(err)));
  }
  // before anything changes its settings: a tty another host uses is left as it is
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0)
    return fail(ConnectionError("serial device " + path +
                                " is in use: another palp host holds its lock (a program "
                                "using the SDK, or palpctl); close it first (`fuser " +
                                path + "` names it)"));
  try {
    make_raw(fd, current, *speed, path);
  } catch (const ConnectionError& e) {
    return fail(e);
  }
  // 8N1: ten bits on the line for every byte
  return std::make_unique<FdTransport>(
      fd, FdPeer{uri.text, "serial device " + path, false, uri.baud / 10});
}

}  // namespace palp::detail
