// SPDX-License-Identifier: Apache-2.0
// hid://[serial]: the byte stream in 64-byte HID reports, through HidApi (hidapi). SPEC.md §3
// and §3.1; the layout is palp/protocol/usb.hpp. About 64 000 bytes/s at most (one report per
// 1 ms interval), for machines where the vendor interface cannot be claimed.
//
// Writing: the stream is cut into 64-byte reports, each handed to hidapi as 65 bytes: the report
// ID 0x00 (the interface declares none; not part of the stream) and the 64 report bytes. A report
// that the write does not fill is zero-padded, but only after a frame's 0x00 delimiter (SPEC
// §3: padding inside a frame would end it early). So the last, partial report of a write is:
//   - sent, zero-padded, up to and including the last 0x00 in it (the SDK writes whole frames,
//     so its writes end with 0x00 and nothing is held);
//   - the bytes after that last 0x00 (the start of a frame not yet complete) are held and go
//     first in the next write. A caller that writes a frame in pieces therefore gets it sent
//     when the piece with its delimiter is written; nothing is ever padded mid-frame.
// hidapi's hid_write takes no timeout: on Linux (hidraw) the kernel bounds one interrupt OUT
// report at 5 s. The write's timeout is checked before each report after the first; when it has
// passed, the write stops with TimeoutError.
//
// Reading: one input report (64 bytes; a report's padding zeros are idle line to the frame
// reader) per call, waiting up to the timeout. A buffer smaller than 64 bytes is served from a
// staging buffer whose rest is returned by the next reads.
#include <algorithm>
#include <climits>
#include <cstring>
#include <vector>

#include "palp/error.hpp"
#include "palp/protocol/usb.hpp"
#include "transport/factories.hpp"
#include "transport/staging.hpp"
#include "transport/hid_api.hpp"
#include "transport/usb_api.hpp"

namespace palp::detail {
namespace {

namespace pu = palp::proto::usb;
constexpr std::size_t kReport = pu::kHidReportSize;

class HidTransport final : public Transport {
 public:
  HidTransport(std::shared_ptr<HidApi> api, HidHandle handle, std::string uri, std::string label)
      : api_(std::move(api)), h_(handle), uri_(std::move(uri)), label_(std::move(label)) {}

  ~HidTransport() override { api_->close(h_); }

  void write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds timeout) override {
    if (bytes.empty()) return;
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::vector<std::uint8_t> data;
    data.reserve(held_.size() + bytes.size());
    data.insert(data.end(), held_.begin(), held_.end());
    data.insert(data.end(), bytes.begin(), bytes.end());
    held_.clear();

    const std::size_t full = data.size() / kReport * kReport;
    // The tail: sent padded up to its last delimiter, the rest held (see the file comment).
    std::size_t send_end = full;
    for (std::size_t k = data.size(); k > full; --k)
      if (data[k - 1] == 0x00) {
        send_end = k;
        break;
      }
    std::vector<std::uint8_t> tail(data.begin() + static_cast<std::ptrdiff_t>(send_end),
                                   data.end());

    std::size_t sent = 0;
    for (std::size_t off = 0; off < send_end; off += kReport) {
      if (off > 0 && std::chrono::steady_clock::now() > deadline)
        throw TimeoutError("the controller at " + label_ + " to take " +
                               std::to_string(send_end) + " bytes (" + std::to_string(sent) +
                               " taken)",
                           static_cast<double>(timeout.count()) / 1000.0, std::nullopt);
      std::uint8_t report[1 + kReport] = {pu::kHidReportId};
      const std::size_t n = std::min(kReport, send_end - off);
      std::memcpy(report + 1, data.data() + off, n);  // the rest stays 0: the padding
      if (api_->write(h_, report, sizeof report) < 0)
        throw ConnectionError(label_ + ": writing a report failed (unplugged?): " +
                              api_->error(&h_));
      sent += n;
    }
    held_ = std::move(tail);  // after an error, the held bytes are dropped with the write
  }

  std::size_t read(std::span<std::uint8_t> buf, std::chrono::milliseconds timeout) override {
    if (buf.empty()) return 0;
    if (staging_.pending()) return staging_.take(buf);
    const bool direct = buf.size() >= kReport;
    std::uint8_t* dst = direct ? buf.data() : staging_.data();
    const int ms = static_cast<int>(std::clamp<long long>(timeout.count(), 0, INT_MAX));
    const int n = api_->read_timeout(h_, dst, kReport, ms);
    if (n < 0)
      throw ConnectionError(label_ + ": the controller was unplugged or stopped answering (" +
                            api_->error(&h_) + ")");
    if (n == 0 || direct) return static_cast<std::size_t>(n);
    return staging_.keep(static_cast<std::size_t>(n), buf);
  }

  std::uint32_t max_device_bytes_per_s() const override { return pu::kHidBytesPerS; }
  const std::string& uri() const override { return uri_; }

 private:

  std::shared_ptr<HidApi> api_;
  HidHandle h_;
  std::string uri_, label_;
  std::vector<std::uint8_t> held_;  ///< bytes of a frame whose delimiter is not written yet
  Staging<kReport> staging_;
};

}  // namespace

std::unique_ptr<Transport> open_hid_transport(const Uri& uri, std::chrono::milliseconds,
                                              std::shared_ptr<HidApi> api) {
  const UsbIdentity id = resolve_identity(uri);
  const std::vector<HidDeviceInfo> infos = api->enumerate(id.vid, id.pid);
  std::vector<std::string> serials;
  for (const HidDeviceInfo& i : infos)
    if (i.vid == id.vid && i.pid == id.pid) serials.push_back(i.serial);
  const SerialChoice choice = choose_by_serial(uri, id, serials, "");
  if (!choice.ok) throw ConnectionError(choice.error);
  const std::string& serial = serials[choice.index];
  const std::string label = "hid://" + serial;
  HidHandle h{};
  if (!api->open(id.vid, id.pid, serial, h)) {
    const std::string why = api->error(nullptr);
    const bool denied = why.find("Permission denied") != std::string::npos;
    throw ConnectionError(label + ": cannot open the controller: " + why +
                          (denied ? std::string(" (") + kPermissionHint + ")" : std::string()));
  }
  return std::make_unique<HidTransport>(std::move(api), h, uri.text, label);
}

std::unique_ptr<Transport> open_hid_transport(const Uri& uri, std::chrono::milliseconds timeout) {
  return open_hid_transport(uri, timeout, make_hidapi_api());
}

}  // namespace palp::detail
