// SPDX-License-Identifier: Apache-2.0
// The usbmon pcap writer (usbmon_pcap.hpp).
#include "usbmon_pcap.hpp"

#include <fstream>

namespace palp::test {
namespace {

void put(std::vector<std::uint8_t>& out, std::uint64_t v, int bytes) {
  for (int k = 0; k < bytes; ++k) out.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
}

constexpr std::uint32_t kPcapMagic = 0xA1B2C3D4;  // microsecond timestamps
constexpr std::uint32_t kLinkTypeUsbLinuxMmapped = 220;
constexpr std::uint8_t kTransferControl = 2;       // usbmon xfer_type
constexpr std::uint8_t kEndpointIn = 0x80;         // epnum bit 7: direction IN
constexpr std::int32_t kEinprogress = -115;        // a submission's status
constexpr std::uint32_t kUrbDirIn = 0x0200;        // xfer_flags of an IN URB
constexpr std::uint8_t kSetupPresent = 0;          // flag_setup: 0 = the setup bytes are valid
constexpr std::uint8_t kSetupAbsent = '-';
constexpr std::uint8_t kDataPresent = 0;           // flag_data: 0 = data follows
constexpr std::uint8_t kDataInPending = '<';       // an IN submission carries no data

}  // namespace

void UsbmonPcap::control_in(const SetupPacket& setup, const std::vector<std::uint8_t>& reply) {
  const std::uint64_t urb = next_urb_;
  next_urb_ += 0x100;
  record(urb, 'S', &setup, kEinprogress, setup.length, {});
  record(urb, 'C', nullptr, 0, static_cast<std::uint32_t>(reply.size()), reply);
}

void UsbmonPcap::record(std::uint64_t urb, char type, const SetupPacket* setup,
                        std::int32_t status, std::uint32_t length,
                        const std::vector<std::uint8_t>& data) {
  time_us_ += 125;
  std::vector<std::uint8_t> h;  // struct usbmon_packet, 64 bytes
  put(h, urb, 8);                                             //  0 id
  put(h, static_cast<std::uint8_t>(type), 1);                 //  8 type
  put(h, kTransferControl, 1);                                //  9 xfer_type
  put(h, kEndpointIn, 1);                                     // 10 epnum (endpoint 0, IN)
  put(h, device_, 1);                                         // 11 devnum
  put(h, bus_, 2);                                            // 12 busnum
  put(h, setup != nullptr ? kSetupPresent : kSetupAbsent, 1);  // 14 flag_setup
  put(h, data.empty() ? kDataInPending : kDataPresent, 1);    // 15 flag_data
  put(h, 1'764'115'200u + time_us_ / 1'000'000u, 8);          // 16 ts_sec
  put(h, time_us_ % 1'000'000u, 4);                           // 24 ts_usec
  put(h, static_cast<std::uint32_t>(status), 4);              // 28 status
  put(h, length, 4);                                          // 32 length
  put(h, data.size(), 4);                                     // 36 len_cap
  if (setup != nullptr) {                                     // 40 setup[8]
    put(h, setup->request_type, 1);
    put(h, setup->request, 1);
    put(h, setup->value, 2);
    put(h, setup->index, 2);
    put(h, setup->length, 2);
  } else {
    put(h, 0, 8);
  }
  put(h, 0, 4);          // 48 interval
  put(h, 0, 4);          // 52 start_frame
  put(h, kUrbDirIn, 4);  // 56 xfer_flags
  put(h, 0, 4);          // 60 ndesc

  const auto captured = static_cast<std::uint32_t>(h.size() + data.size());
  put(records_, 1'764'115'200u + time_us_ / 1'000'000u, 4);  // pcap record: ts_sec
  put(records_, time_us_ % 1'000'000u, 4);                   // ts_usec
  put(records_, captured, 4);                                // incl_len
  put(records_, captured, 4);                                // orig_len
  records_.insert(records_.end(), h.begin(), h.end());
  records_.insert(records_.end(), data.begin(), data.end());
}

std::vector<std::uint8_t> UsbmonPcap::bytes() const {
  std::vector<std::uint8_t> out;
  put(out, kPcapMagic, 4);
  put(out, 2, 2);  // version 2.4
  put(out, 4, 2);
  put(out, 0, 4);  // thiszone
  put(out, 0, 4);  // sigfigs
  put(out, 65535, 4);  // snaplen
  put(out, kLinkTypeUsbLinuxMmapped, 4);
  out.insert(out.end(), records_.begin(), records_.end());
  return out;
}

bool UsbmonPcap::write(const std::string& path) const {
  const std::vector<std::uint8_t> b = bytes();
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
  return static_cast<bool>(f);
}

}  // namespace palp::test
