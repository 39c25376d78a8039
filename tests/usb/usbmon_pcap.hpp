// SPDX-License-Identifier: Apache-2.0
// A synthesised usbmon capture: control transfers as a Linux host's usbmon records them, written
// as a classic pcap file of link type LINKTYPE_USB_LINUX_MMAPPED (220), for tshark to decode
// (this machine has no USB subsystem to capture from).
//
// Each transfer is two records with the same URB id: the submission ('S', the 8-byte SETUP packet,
// status -EINPROGRESS) and the completion ('C', status 0, the data stage's bytes). The 64-byte
// record header is struct usbmon_packet of the kernel's Documentation/usb/usbmon.rst ("binary
// API v1", the mmapped form); fields in the host's byte order, little-endian here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace palp::test {

struct SetupPacket {  // facts §1.1
  std::uint8_t request_type = 0, request = 0;
  std::uint16_t value = 0, index = 0, length = 0;
};

class UsbmonPcap {
 public:
  UsbmonPcap(std::uint16_t bus, std::uint8_t device) : bus_(bus), device_(device) {}
  /// A control IN transfer on endpoint 0 whose data stage returned reply.
  void control_in(const SetupPacket& setup, const std::vector<std::uint8_t>& reply);
  /// The pcap file's bytes (global header + records).
  std::vector<std::uint8_t> bytes() const;
  /// Writes bytes() to path; false when the file cannot be written.
  bool write(const std::string& path) const;

 private:
  void record(std::uint64_t urb, char type, const SetupPacket* setup, std::int32_t status,
              std::uint32_t length, const std::vector<std::uint8_t>& data);

  std::uint16_t bus_;
  std::uint8_t device_;
  std::uint64_t next_urb_ = 0xFFFF'8880'0A00'0000u;
  std::uint32_t time_us_ = 0;
  std::vector<std::uint8_t> records_;
};

}  // namespace palp::test
