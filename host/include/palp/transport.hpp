// SPDX-License-Identifier: Apache-2.0
// Transports: the byte stream of frames to and from one controller (protocol/SPEC.md §3),
// behind one small interface, chosen by URI:
//
//   usb://[serial][?vid=0x1209&pid=0x0001]   libusb, the vendor interface's bulk endpoints
//   hid://[serial][?vid=0x1209&pid=0x0001]   hidapi, 64-byte reports (about 64 KB/s at most)
//   tcp://host:port                          the framed byte stream over TCP: palp-sim, or the
//                                            firmware under QEMU (-serial tcp:...,server=on)
//   serial:///dev/ttyX[?baud=N]              a UART-attached board: the tty opened raw (8N1, no
//                                            flow control), N baud (default 115200, a termios
//                                            speed); locked (flock) so no second host shares it;
//                                            it carries at most N/10 bytes/s
//   sim://host:port                          palp-sim over TCP (the same as tcp://host:port)
//   sim:///path/to/socket                    palp-sim over a Unix-domain socket
//   sim+inproc://PHANTOM[?seed=N&...]        palp-sim linked into this program: no process, no
//                                            socket, virtual time as fast as the reader reads
//
// sim+inproc:// works only in a program that links the palp_sim_inproc library (built with
// palp-sim; it registers its factory when linked, see set_sim_inproc_factory); elsewhere
// open_transport throws ConfigError saying so. Its parameters and its time model are in
// palp/sim_inproc.hpp, which also offers the same as an API (palp::sim::InprocSimulator) for a
// test that wants the simulator's control channel or the robot bridge on the same simulation.
// An empty serial picks the only controller present and is an error when there are several.
// Thread-safety: one thread may read while another writes; two concurrent readers (or writers)
// are not allowed. The Probe client owns its transport and obeys this.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace palp {

/// serial:// without ?baud=: the usual UART rate (a pty, and QEMU's UART, ignore it).
inline constexpr std::uint32_t kDefaultBaud = 115200;

/// The baud rates serial:// accepts: the termios speeds, ascending.
std::span<const std::uint32_t> serial_bauds();

/// A parsed transport URI.
struct Uri {
  enum class Scheme { usb, hid, sim_tcp, sim_unix, sim_inproc, tcp, serial };
  Scheme scheme = Scheme::sim_tcp;
  std::string serial;          ///< usb, hid: the serial number wanted ("" = the only one)
  std::string host;            ///< sim_tcp, tcp
  std::uint16_t port = 0;      ///< sim_tcp, tcp
  std::string path;            ///< sim_unix: the socket; serial: the tty device
  std::uint32_t baud = kDefaultBaud;  ///< serial: a termios speed (serial_bauds())
  std::string phantom;         ///< sim_inproc: the phantom's name ("none": free air)
  /// sim_inproc: key=value parameters in order, checked by the in-process simulator
  std::vector<std::pair<std::string, std::string>> parameters;
  std::optional<std::uint16_t> vid, pid;  ///< usb, hid: overrides of the USB identity
  std::string text;            ///< the URI as given
};

/// Parses a URI; throws ConfigError naming the URI and what is wrong with it.
Uri parse_uri(const std::string& text);

class Transport {
 public:
  virtual ~Transport() = default;

  /// Writes every byte or throws: ConnectionError when the link is gone, TimeoutError when the
  /// device did not take the bytes within timeout.
  virtual void write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds timeout) = 0;

  /// Reads what has arrived into buf, waiting up to timeout for the first byte. Returns the
  /// number of bytes, 0 when nothing arrived in time. Throws ConnectionError when the link is
  /// gone (unplugged, simulator stopped).
  virtual std::size_t read(std::span<std::uint8_t> buf, std::chrono::milliseconds timeout) = 0;

  /// The most bytes per second this transport carries from the device (a stream whose byte rate
  /// exceeds it is refused before it starts).
  virtual std::uint32_t max_device_bytes_per_s() const = 0;

  /// The URI this transport was opened from, for messages.
  virtual const std::string& uri() const = 0;
};

/// Opens the transport a URI names. Throws ConfigError for a malformed URI (and for a serial://
/// path that is not a terminal), ConnectionError when the device is absent or cannot be opened:
/// nothing listening, no such tty, permission denied, a tty another program holds (the message
/// says why and what to try).
std::unique_ptr<Transport> open_transport(const Uri& uri, std::chrono::milliseconds timeout);
std::unique_ptr<Transport> open_transport(const std::string& uri,
                                          std::chrono::milliseconds timeout);

/// What opens sim+inproc:// URIs. palp_sim_inproc calls set_sim_inproc_factory when its code
/// is linked (at static initialisation); applications do not call it.
using TransportFactory = std::unique_ptr<Transport> (*)(const Uri& uri,
                                                        std::chrono::milliseconds timeout);
void set_sim_inproc_factory(TransportFactory factory);

}  // namespace palp
