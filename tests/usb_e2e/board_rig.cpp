// SPDX-License-Identifier: Apache-2.0
// The board behind the bus (board_rig.hpp).
#include "board_rig.hpp"

#include <algorithm>
#include <stdexcept>

#include "palp/protocol/usb.hpp"
#include "palp/sim/plant_link.hpp"
#include "palp/usb/descriptors.hpp"

namespace palp::usb_e2e {

namespace {

namespace ut = usb::test;

/// The device thread's pause between passes (the board's main loop is faster; 256 bytes a pass
/// every 100 us carries 2.5 MB/s, five times the densest stream).
constexpr auto kPassPause = std::chrono::microseconds(100);
/// What the app's main loop moves to the link per call (firmware/app: App::kChunk).
constexpr std::size_t kLinkChunk = 256;

void require(bool ok, const std::string& step) {
  if (!ok) throw std::runtime_error("usb_e2e rig: enumeration failed at " + step);
}

}  // namespace

BoardRig::BoardRig(const RigOptions& options) : options_(options) {
  identity_.board = "stm32g474-rig";  // DeviceInfo.board holds 16 characters
  identity_.serial = options_.serial.c_str();
  identity_.git_hash = "usb-e2e";
  identity_.max_stream_rate_Hz = options_.max_stream_rate_Hz;
  // what the board does at boot: the UID as the USB serial string (descriptors.hpp)
  require(usb::set_serial_number(options_.serial.c_str()), "set_serial_number");
  sim_ = std::make_unique<sim::Simulation>(identity_, std::make_unique<sim::ModelPlant>("none", 1));
  enumerate();
  thread_ = std::thread([this] { device_loop(); });
}

BoardRig::~BoardRig() {
  stop_ = true;
  thread_.join();
}

// What a host's USB stack does when the board is plugged in, before any application opens it:
// Linux's hub driver and usbhid (usb-dfu-facts.md §1.10).
void BoardRig::enumerate() {
  std::lock_guard lock(mu_);
  device_.start();
  host_.reset();
  const auto first = host_.control_in(ut::get_descriptor(0x01, 0, 64));
  require(first.outcome == ut::Outcome::ok && first.data.size() == 18, "GET_DESCRIPTOR(device, 64)");
  require(host_.control_out(ut::set_address(kAddress)).outcome == ut::Outcome::ok, "SET_ADDRESS");
  host_.address = kAddress;
  const auto device = host_.control_in(ut::get_descriptor(0x01, 0, 18));
  require(device.outcome == ut::Outcome::ok && device.data.size() == 18, "GET_DESCRIPTOR(device)");
  device_descriptor_ = device.data;
  const auto head = host_.control_in(ut::get_descriptor(0x02, 0, 9));
  require(head.outcome == ut::Outcome::ok && head.data.size() == 9, "GET_DESCRIPTOR(configuration, 9)");
  const auto total = static_cast<std::uint16_t>(head.data[2] | head.data[3] << 8);
  const auto config = host_.control_in(ut::get_descriptor(0x02, 0, total));
  require(config.outcome == ut::Outcome::ok && config.data.size() == total,
          "GET_DESCRIPTOR(configuration)");
  require(host_.control_out(ut::set_configuration(1)).outcome == ut::Outcome::ok,
          "SET_CONFIGURATION(1)");
  // usbhid binds the HID interface: SET_IDLE(0), then the report descriptor
  const std::uint16_t hid = proto::usb::kHidInterface;
  require(host_.control_out({0x21, 0x0A, 0, hid, 0}).outcome == ut::Outcome::ok, "SET_IDLE");
  const auto report = host_.control_in(ut::get_descriptor(0x22, 0, 255, hid, 0x81));
  require(report.outcome == ut::Outcome::ok && !report.data.empty(), "GET_DESCRIPTOR(HID report)");
}

std::uint64_t BoardRig::wall_us() const {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - t0_).count());
}

void BoardRig::device_loop() {
  while (!stop_) {
    {
      std::lock_guard lock(mu_);
      device_pass(wall_us());
    }
    pass_.notify_all();
    std::this_thread::sleep_for(kPassPause);
  }
}

// One pass of the board's main loop with the ticks that fell due since the last one.
void BoardRig::device_pass(std::uint64_t now_us) {
  std::uint8_t chunk[256];
  for (std::size_t n; (n = device_.read(chunk, sizeof chunk)) > 0;)
    sim_->host_bytes(chunk, n, now_us);

  const std::uint32_t rate = sim_->controller().control_rate_Hz();
  const std::uint64_t ran = ticks_.load();
  if (rate != rate_Hz_) {  // a new control rate: its schedule starts now
    rate_Hz_ = rate;
    anchor_us_ = now_us;
    anchor_ticks_ = ran;
  }
  const std::uint64_t scheduled = anchor_ticks_ + (now_us - anchor_us_) * rate / 1'000'000u;
  std::uint64_t due = scheduled > ran ? scheduled - ran : 0;
  const std::uint64_t most = rate / 100;  // 10 ms a pass; beyond that the board dropped ticks
  if (due > most) {
    anchor_us_ = now_us;
    anchor_ticks_ = ran + most;
    due = most;
  }
  if (outbox_.size() > kBacklogBytes && due > 0) {  // the host does not drain: hold the tick
    ticks_held_ += due;
    anchor_us_ = now_us;
    anchor_ticks_ = ran;
    due = 0;
  }
  if (due > 0) ticks_ += sim_->run(static_cast<std::uint32_t>(due), now_us);

  const std::vector<std::uint8_t> out = sim_->take_device_bytes();
  outbox_.insert(outbox_.end(), out.begin(), out.end());
  // as the app's main loop: one link_write of at most 256 bytes a pass (App::flush, App::kChunk),
  // so a frame reaches the USB ring in pieces cut anywhere, and the host may drain between them
  const std::size_t taken = device_.write(outbox_.data(), std::min(kLinkChunk, outbox_.size()));
  outbox_.erase(outbox_.begin(), outbox_.begin() + static_cast<std::ptrdiff_t>(taken));
  device_.service();  // the board pends the USB interrupt after link_read/link_write
  ++passes_;
}

bool BoardRig::wait_for_device(std::unique_lock<std::mutex>& lock, Clock::time_point deadline) {
  const std::uint64_t seen = passes_;
  return pass_.wait_until(lock, deadline, [&] { return passes_ != seen; });
}

bool BoardRig::control_in(const usb::SetupPacket& setup, std::vector<std::uint8_t>& data) {
  std::lock_guard lock(mu_);
  auto r = host_.control_in(setup);
  data = std::move(r.data);
  return r.outcome == ut::Outcome::ok;
}

Transfer BoardRig::transfer_out(std::uint8_t number, const std::uint8_t* bytes, std::size_t size,
                                std::size_t& sent, Clock::time_point deadline) {
  constexpr std::size_t kPacket = proto::usb::kBulkPacketSize;
  std::unique_lock lock(mu_);
  sent = 0;
  for (;;) {
    const std::size_t n = std::min(kPacket, size - sent);
    const ut::Handshake h = bus_.out(kAddress, number, bytes + sent, n);
    device_.service();
    if (h == ut::Handshake::nak) {
      if (!wait_for_device(lock, deadline) && Clock::now() >= deadline) return Transfer::timeout;
      continue;
    }
    if (h == ut::Handshake::stall) return Transfer::stall;
    if (h != ut::Handshake::ack) return Transfer::no_answer;
    sent += n;
    if (n < kPacket || sent == size) return Transfer::ok;  // a short packet (or the ZLP) ends it
  }
}

Transfer BoardRig::transfer_in(std::uint8_t number, std::uint8_t* bytes, std::size_t capacity,
                               std::size_t& got, Clock::time_point deadline, bool one_packet) {
  std::unique_lock lock(mu_);
  got = 0;
  for (;;) {
    const ut::InAnswer a = bus_.in(kAddress, number);
    device_.service();
    if (a.handshake == ut::Handshake::nak) {
      if (!wait_for_device(lock, deadline) && Clock::now() >= deadline) return Transfer::timeout;
      continue;
    }
    if (a.handshake == ut::Handshake::stall) return Transfer::stall;
    if (a.handshake != ut::Handshake::ack) return Transfer::no_answer;
    if (number == lose_number_ && lose_countdown_ > 0 && --lose_countdown_ == 0) continue;
    if (a.data.size() > capacity - got) return Transfer::overflow;
    std::copy(a.data.begin(), a.data.end(), bytes + got);
    got += a.data.size();
    if (one_packet || a.data.size() < proto::usb::kBulkPacketSize || got == capacity)
      return Transfer::ok;
  }
}

void BoardRig::lose_in_packet(std::uint8_t number, std::uint32_t nth) {
  std::lock_guard lock(mu_);
  lose_number_ = number;
  lose_countdown_ = nth;
}

std::vector<std::string> BoardRig::violations() {
  std::lock_guard lock(mu_);
  return bus_.violations();
}

usb::DeviceCounters BoardRig::device_counters() {
  std::lock_guard lock(mu_);
  return device_.counters();
}

}  // namespace palp::usb_e2e
