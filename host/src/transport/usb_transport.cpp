// SPDX-License-Identifier: Apache-2.0
// usb://[serial]: the byte stream over the vendor interface's bulk endpoints, through UsbApi
// (libusb). SPEC.md §3 and §3.1; the layout is palp/protocol/usb.hpp.
//
// Opening: every device with the identity (resolve_identity) is opened to read its serial
// number; the one the URI names (or the only one) is kept, the others closed. A kernel driver on
// the vendor interface is detached, then the interface is claimed.
//
// Writing: bulk OUT transfers of at most kMaxTransfer bytes, the first with the write's timeout,
// each later one with what is left of it; a write whose length is a non-zero multiple of 64 (the
// packet size) is followed by a zero-length transfer (a ZLP), so the firmware's transfer
// completes at once (usb.hpp, SPEC.md §3.1). A 130-byte write is one transfer of 130 bytes; a 128-byte write is
// one transfer of 128 bytes and one of 0.
//
// Reading: one bulk IN transfer. Its length is the caller's buffer rounded down to a multiple of
// 64 (at most kMaxTransfer), so a packet never overflows it; a buffer smaller than 64 bytes is
// served from a 64-byte staging buffer whose rest is returned by the next reads. A timeout
// returns the bytes that came (often 0). libusb takes 0 ms as "no timeout": the SDK passes at
// least 1 ms, so every call returns.
//
// libusb_open and the string descriptor reads take no timeout argument; libusb bounds the
// control transfer of a string read at 1 s.
#include <algorithm>
#include <climits>
#include <cstdio>
#include <cstring>

#include "palp/error.hpp"
#include "palp/protocol/usb.hpp"
#include "transport/factories.hpp"
#include "transport/staging.hpp"
#include "transport/usb_api.hpp"

namespace palp::detail {

namespace pu = palp::proto::usb;

UsbIdentity resolve_identity(const Uri& uri) {
  if (uri.vid && uri.pid) return {*uri.vid, *uri.pid};
  const DiscoveryOptions defaults;  // the environment, else the header
  return {uri.vid.value_or(defaults.vid), uri.pid.value_or(defaults.pid)};
}

std::string describe_identity(UsbIdentity id) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "vid 0x%04x pid 0x%04x", id.vid, id.pid);
  return buf;
}

SerialChoice choose_by_serial(const Uri& uri, UsbIdentity id,
                              const std::vector<std::string>& serials,
                              const std::string& unreadable_why) {
  const std::string scheme = uri.scheme == Uri::Scheme::hid ? "hid://" : "usb://";
  std::string listed, first;
  std::size_t unreadable = 0;
  for (const std::string& s : serials) {
    if (s.empty()) {
      ++unreadable;
      continue;
    }
    if (first.empty()) first = s;
    listed += (listed.empty() ? "" : ", ") + s;
  }
  if (listed.empty()) listed = "none readable";
  std::string why_unreadable;
  if (unreadable > 0 && !unreadable_why.empty())
    why_unreadable = "; " + std::to_string(unreadable) + " could not be opened: " + unreadable_why;

  SerialChoice c;
  if (serials.empty()) {
    c.error = uri.text + ": no palp controller found (" + describe_identity(id) +
              "); check that it is plugged in and powered";
    return c;
  }
  if (!uri.serial.empty()) {
    const auto it = std::find(serials.begin(), serials.end(), uri.serial);
    if (it != serials.end()) {
      c.ok = true;
      c.index = static_cast<std::size_t>(it - serials.begin());
      return c;
    }
    c.error = uri.text + ": no palp controller with serial '" + uri.serial + "' (found: " +
              listed + why_unreadable + ")";
    return c;
  }
  if (serials.size() == 1) {
    if (serials[0].empty() && !unreadable_why.empty()) {
      c.error = uri.text + ": cannot open the controller: " + unreadable_why;
      return c;
    }
    c.ok = true;
    return c;
  }
  c.error = uri.text + ": " + std::to_string(serials.size()) +
            " palp controllers are connected (serials: " + listed + why_unreadable +
            "); name one, e.g. " + scheme + (first.empty() ? std::string("SERIAL") : first);
  return c;
}

namespace {

/// The longest single transfer (a multiple of the packet size).
constexpr std::size_t kMaxTransfer = 16384;
static_assert(kMaxTransfer % pu::kBulkPacketSize == 0);

/// A libusb timeout for what is left until deadline: at least 1 ms (0 would mean "forever").
unsigned ms_until(std::chrono::steady_clock::time_point deadline) {
  const auto left = std::chrono::ceil<std::chrono::milliseconds>(
      deadline - std::chrono::steady_clock::now());
  return static_cast<unsigned>(std::clamp<long long>(left.count(), 1, UINT_MAX));
}

unsigned ms_of(std::chrono::milliseconds t) {
  return static_cast<unsigned>(std::clamp<long long>(t.count(), 1, UINT_MAX));
}

/// Why libusb_open failed, with what to do about it.
std::string open_error(int r) {
  if (r == kUsbErrorAccess)
    return usb_error_name(r) + " (permission denied: " + kPermissionHint + ")";
  if (r == kUsbErrorNoDevice) return usb_error_name(r) + " (unplugged while being opened)";
  return usb_error_name(r);
}

class UsbTransport final : public Transport {
 public:
  UsbTransport(std::shared_ptr<UsbApi> api, UsbHandle handle, std::string uri, std::string label)
      : api_(std::move(api)), h_(handle), uri_(std::move(uri)), label_(std::move(label)) {}

  ~UsbTransport() override {
    api_->release_interface(h_, pu::kVendorInterface);
    api_->close(h_);
    api_->exit();
  }

  void write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds timeout) override {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::size_t off = 0;
    while (off < bytes.size()) {
      const int chunk = static_cast<int>(std::min(bytes.size() - off, kMaxTransfer));
      int done = 0;
      // libusb does not modify the bytes of an OUT transfer.
      const int r = api_->bulk_transfer(h_, pu::kBulkOutEndpoint,
                                        const_cast<std::uint8_t*>(bytes.data() + off), chunk,
                                        done, off == 0 ? ms_of(timeout) : ms_until(deadline));
      off += static_cast<std::size_t>(std::max(done, 0));
      if (r == kUsbErrorTimeout) throw_write_timeout(bytes.size(), off, timeout);
      if (r < 0) fail("writing", r);
    }
    if (!bytes.empty() && bytes.size() % pu::kBulkPacketSize == 0) {
      int done = 0;
      const int r = api_->bulk_transfer(h_, pu::kBulkOutEndpoint, &zlp_, 0, done,
                                        ms_until(deadline));
      if (r == kUsbErrorTimeout) throw_write_timeout(bytes.size(), off, timeout);
      if (r < 0) fail("writing", r);
    }
  }

  std::size_t read(std::span<std::uint8_t> buf, std::chrono::milliseconds timeout) override {
    if (buf.empty()) return 0;
    if (staging_.pending()) return staging_.take(buf);
    const bool direct = buf.size() >= pu::kBulkPacketSize;
    std::uint8_t* dst = direct ? buf.data() : staging_.data();
    const std::size_t len =
        direct ? std::min(buf.size() / pu::kBulkPacketSize * pu::kBulkPacketSize, kMaxTransfer)
               : pu::kBulkPacketSize;
    int got = 0;
    const int r = api_->bulk_transfer(h_, pu::kBulkInEndpoint, dst, static_cast<int>(len), got,
                                      ms_of(timeout));
    if (r < 0 && r != kUsbErrorTimeout && r != kUsbErrorInterrupted) fail("reading", r);
    if (got <= 0) return 0;
    if (direct) return static_cast<std::size_t>(got);
    return staging_.keep(static_cast<std::size_t>(got), buf);
  }

  std::uint32_t max_device_bytes_per_s() const override { return pu::kBulkBytesPerS; }
  const std::string& uri() const override { return uri_; }

 private:

  [[noreturn]] void throw_write_timeout(std::size_t total, std::size_t sent,
                                        std::chrono::milliseconds timeout) const {
    throw TimeoutError("the controller at " + label_ + " to take " + std::to_string(total) +
                           " bytes (" + std::to_string(sent) + " taken)",
                       static_cast<double>(timeout.count()) / 1000.0, std::nullopt);
  }

  [[noreturn]] void fail(const char* doing, int r) const {
    if (r == kUsbErrorNoDevice)
      throw ConnectionError(label_ + ": the controller was unplugged (" + usb_error_name(r) + ")");
    if (r == kUsbErrorPipe)
      throw ConnectionError(label_ + ": " + doing + " failed: the endpoint stalled (" +
                            usb_error_name(r) + "); re-plug the controller");
    throw ConnectionError(label_ + ": " + doing + " failed: " + usb_error_name(r));
  }

  std::shared_ptr<UsbApi> api_;
  UsbHandle h_;
  std::string uri_, label_;
  std::uint8_t zlp_ = 0;
  Staging<pu::kBulkPacketSize> staging_;
};

}  // namespace

std::unique_ptr<Transport> open_usb_transport(const Uri& uri, std::chrono::milliseconds,
                                              std::shared_ptr<UsbApi> api) {
  const UsbIdentity id = resolve_identity(uri);
  if (const int r = api->init(); r < 0)
    throw ConnectionError(uri.text + ": USB is not available on this machine (libusb_init: " +
                          usb_error_name(r) + ")");
  std::vector<UsbDevice> devices;
  if (const int r = api->get_device_list(devices); r < 0) {
    api->exit();
    throw ConnectionError(uri.text + ": cannot list the USB devices: " + usb_error_name(r));
  }
  struct Found {
    UsbHandle handle{};
    bool open = false;
  };
  std::vector<Found> found;
  std::vector<std::string> serials;
  std::string unreadable_why;
  for (const UsbDevice d : devices) {
    UsbDeviceDescriptor desc;
    if (api->get_device_descriptor(d, desc) < 0 || desc.vid != id.vid || desc.pid != id.pid)
      continue;
    Found f;
    std::string serial;
    if (const int r = api->open(d, f.handle); r < 0) {
      if (unreadable_why.empty()) unreadable_why = open_error(r);
    } else {
      f.open = true;
      if (desc.i_serial != 0 &&
          api->get_string_descriptor_ascii(f.handle, desc.i_serial, serial) < 0)
        serial.clear();
    }
    found.push_back(f);
    serials.push_back(serial);
  }
  api->free_device_list();

  const SerialChoice choice = choose_by_serial(uri, id, serials, unreadable_why);
  for (std::size_t k = 0; k < found.size(); ++k)
    if (found[k].open && !(choice.ok && k == choice.index)) api->close(found[k].handle);
  if (!choice.ok || !found[choice.index].open) {
    api->exit();
    throw ConnectionError(choice.ok ? uri.text + ": cannot open the controller: " + unreadable_why
                                    : choice.error);
  }
  const UsbHandle h = found[choice.index].handle;
  const std::string label = "usb://" + serials[choice.index];

  const auto give_up = [&](const std::string& why) {
    api->close(h);
    api->exit();
    throw ConnectionError(label + ": cannot claim the vendor interface " +
                          std::to_string(pu::kVendorInterface) + ": " + why);
  };
  if (api->kernel_driver_active(h, pu::kVendorInterface) == 1) {
    if (const int r = api->detach_kernel_driver(h, pu::kVendorInterface);
        r < 0 && r != kUsbErrorNotFound)
      give_up("detaching the kernel driver failed: " + open_error(r));
  }
  if (const int r = api->claim_interface(h, pu::kVendorInterface); r < 0) {
    if (r == kUsbErrorBusy)
      give_up(usb_error_name(r) + " (another program holds it, perhaps another palpctl or SDK "
              "session; close it, or reach the controller over hid://" +
              serials[choice.index] + ")");
    give_up(open_error(r));
  }
  return std::make_unique<UsbTransport>(std::move(api), h, uri.text, label);
}

std::unique_ptr<Transport> open_usb_transport(const Uri& uri, std::chrono::milliseconds timeout) {
  return open_usb_transport(uri, timeout, make_libusb_api());
}

}  // namespace palp::detail
