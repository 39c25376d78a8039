// SPDX-License-Identifier: Apache-2.0
// The USB device core (firmware/usb/README.md): Device<H> over any UsbHardware H (hardware.hpp,
// contract 1) answers the control requests of enumeration and carries the protocol's byte stream
// (SPEC.md §3, §3.1; palp/protocol/usb.hpp) over the vendor interface's bulk endpoints and the
// HID interface's interrupt endpoints. The descriptors come from descriptors.hpp (contract 2);
// the core never builds one.
//
// Contexts. service() runs in the USB interrupt (or wherever the board polls the hardware): it
// handles every pending hardware event and moves stream bytes between the endpoints and two
// fixed-size rings. read() and write() run in the main loop (the app's link_read/link_write);
// each ring has one producer and one consumer (byte_ring.hpp), so these need no lock. After
// read() or write() moved bytes the board lets service() run soon (e.g. pends the USB
// interrupt): that is where paused OUT endpoints re-arm and the IN pipe starts.
//
// Control endpoint (usb-dfu-facts.md §1): SETUP -> optional data stage -> status stage.
//   - IN data: at most wLength bytes, in 64-byte packets, ending with a zero-length packet when
//     the reply is shorter than wLength and a non-zero multiple of 64 (requests.hpp). ep0 OUT is
//     armed for the status stage from the start, so a host that ends the data stage early
//     (Windows' first GET_DESCRIPTOR(DEVICE, 64)) completes it.
//   - OUT data (HID SET_REPORT only): at most 64 bytes; the status stage is held (NAKed) until
//     the ring has room for the report, so no byte is dropped.
//   - Anything unknown, malformed, or not allowed in the current state: STALL ep0 (facts §1.11),
//     which the next SETUP clears. A SETUP aborts the transfer in progress.
//   - SET_ADDRESS takes effect after its status stage (the zero-length IN) has been sent.
//   Requests: GET_DESCRIPTOR (device-recipient: device, configuration, string, BOS;
//   interface-recipient on the HID interface: HID 0x21 and report 0x22), SET_ADDRESS,
//   GET/SET_CONFIGURATION (value 1 opens 0x01/0x81 bulk 64 and 0x02/0x82 interrupt 64; 0 stalls
//   them), GET_STATUS, SET/CLEAR_FEATURE(ENDPOINT_HALT) (clearing re-opens the endpoint: DATA0),
//   GET/SET_INTERFACE (alternate setting 0 only), the MS OS 2.0 descriptor set (0xC0,
//   kMsOs20VendorCode, wIndex 7; facts §4.4), and the HID class requests SET_IDLE, GET_IDLE,
//   GET_REPORT(Input: a report of padding, 64 zeros) and SET_REPORT(Output: 64 stream bytes, as
//   on the interrupt OUT endpoint) (facts §2.2). Remote wakeup and test mode are not offered.
//
// The stream.
//   - Received: every OUT packet's bytes go into the receive ring (a bulk zero-length packet is
//     no bytes; a HID report's 64 bytes all go, its padding being idle line). An OUT endpoint is
//     armed only while the ring has room for one more packet on every armed endpoint; otherwise
//     it stays un-armed (the host is NAKed) until read() makes room: flow control, nothing
//     dropped.
//   - Sent: on the interface that last received an OUT packet (the host talks on the interface
//     it opened; the SDK opens one, usb:// or hid://). Until the host has sent something, or
//     after a reset or SET_CONFIGURATION, nothing is sent: a packet written to an endpoint no one
//     reads would sit there. Bulk: 64-byte packets while 64 or more bytes are waiting, else one
//     short packet with what is waiting; a run of packets that ends on a full packet is followed
//     by a zero-length packet (usb.hpp's ZLP rule: the run is "the write"). HID: 64-byte reports,
//     zero-padded only after a frame's 0x00 (requests.hpp hid_report_take); a frame's start
//     waits for its end. A packet's bytes leave the ring only when the host has taken the
//     packet; when the host switches interfaces (or a halt is cleared), the bytes of a packet it
//     never took are sent again on the new pipe (counters().tx_resent_bytes): the old endpoint
//     may still hold that packet for a later reader, whose frame reader then rejects at most one
//     broken frame (SPEC §4.5).
//
// No heap, no exceptions, no blocking; RxCapacity and TxCapacity are the rings' sizes (powers of
// two, at least 128).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "palp/protocol/usb.hpp"
#include "palp/usb/byte_ring.hpp"
#include "palp/usb/descriptors.hpp"
#include "palp/usb/hardware.hpp"
#include "palp/usb/requests.hpp"

namespace palp::usb {

/// chapter 9 device states (facts §1.10) as the core tracks them.
enum class DeviceState : std::uint8_t { detached, default_state, address, configured };

/// Which interface carries the device's outgoing stream (see the file comment).
enum class StreamPipe : std::uint8_t { none, bulk, hid };

/// What the core counts, for a health report (all wrap at 2^32).
struct DeviceCounters {
  std::uint32_t bus_resets = 0;
  std::uint32_t suspends = 0;
  std::uint32_t setups = 0;          ///< SETUP packets handled
  std::uint32_t control_stalls = 0;  ///< requests answered with STALL
  std::uint32_t rx_bytes = 0;        ///< stream bytes received (HID padding included)
  std::uint32_t tx_bytes = 0;        ///< stream bytes the host took
  std::uint32_t rx_pauses = 0;       ///< OUT packets left un-armed for want of ring room
  std::uint32_t pipe_switches = 0;   ///< changes of the sending interface
  std::uint32_t tx_resent_bytes = 0; ///< bytes sent again after a switch or a cleared halt
  std::uint32_t ignored_events = 0;  ///< events for endpoints not in use (e.g. unconfigured)
};

template <UsbHardware H, std::size_t RxCapacity = 1024, std::size_t TxCapacity = 2048>
class Device {
  static_assert(RxCapacity >= 2 * proto::usb::kBulkPacketSize, "the receive ring takes 2 packets");
  static_assert(TxCapacity >= 2 * proto::usb::kBulkPacketSize, "the send ring holds 2 packets");

 public:
  explicit Device(H& hardware) : hw_(hardware) {}

  /// Connects to the bus (the D+ pull-up); the host resets the device and enumerates it.
  void start() { hw_.connect(true); }
  /// Disconnects; the device is detached until start().
  void stop() {
    hw_.connect(false);
    state_ = DeviceState::detached;
  }

  /// USB interrupt: handles every pending event, then feeds the IN pipe and re-arms paused OUT
  /// endpoints.
  void service() {
    for (Event e = hw_.poll(); e.kind != EventKind::none; e = hw_.poll()) handle(e);
    finish_held_set_report();
    resume_rx();
    pump_tx();
  }

  /// Main loop: moves up to `size` received stream bytes into `bytes`; returns how many.
  std::size_t read(std::uint8_t* bytes, std::size_t size) { return rx_.pop(bytes, size); }
  /// Main loop: takes up to `size` bytes to send; returns how many (0: the ring is full).
  std::size_t write(const std::uint8_t* bytes, std::size_t size) { return tx_.push(bytes, size); }

  DeviceState state() const { return state_; }
  bool configured() const { return state_ == DeviceState::configured; }
  bool suspended() const { return suspended_; }
  StreamPipe sending_pipe() const { return pipe_; }
  const DeviceCounters& counters() const { return counters_; }
  std::size_t rx_waiting() const { return rx_.size(); }
  std::size_t tx_waiting() const { return tx_.size(); }

 private:
  static constexpr std::size_t kPacket = proto::usb::kBulkPacketSize;
  static constexpr std::uint8_t kBulkEp = proto::usb::kBulkOutEndpoint;  // number 1
  static constexpr std::uint8_t kHidEp = proto::usb::kHidOutEndpoint;    // number 2
  static_assert((proto::usb::kBulkInEndpoint & 0x7F) == kBulkEp &&
                (proto::usb::kHidInEndpoint & 0x7F) == kHidEp);
  static constexpr std::uint8_t kConfigurationValue = 1;
  static constexpr std::size_t kEndpoints = 3;  // numbers 0..2

  enum class Control : std::uint8_t { idle, data_in, data_out, status_in, status_out };

  // ---- events ----------------------------------------------------------------------------------
  void handle(const Event& e) {
    switch (e.kind) {
      case EventKind::reset: on_reset(); return;
      case EventKind::suspend:
        suspended_ = true;
        ++counters_.suspends;
        return;
      case EventKind::resume: suspended_ = false; return;
      case EventKind::setup:
        if (e.endpoint == 0) on_setup();
        else ++counters_.ignored_events;
        return;
      case EventKind::out:
        if (e.endpoint == 0) on_control_out();
        else on_stream_out(e.endpoint);
        return;
      case EventKind::in_complete:
        if (e.endpoint == 0) on_control_in_complete();
        else on_stream_in_complete(e.endpoint);
        return;
      case EventKind::none: return;
    }
  }

  void on_reset() {
    ++counters_.bus_resets;
    state_ = DeviceState::default_state;
    suspended_ = false;
    control_ = Control::idle;
    held_set_report_ = false;  // its transfer died with the reset
    pending_address_ = -1;
    close_stream_endpoints();
  }

  // Forgets the stream endpoints' state (the hardware closed them, or they are re-opened):
  // a packet in flight is sent again, by whichever pipe sends next.
  void close_stream_endpoints() {
    for (std::size_t n = 1; n < kEndpoints; ++n) {
      armed_[n] = paused_[n] = false;
      in_busy_[n] = false;
      halted_in_[n] = halted_out_[n] = false;
    }
    abandon_in_flight();
    pipe_ = StreamPipe::none;
    zlp_owed_ = false;
  }

  void abandon_in_flight() {
    counters_.tx_resent_bytes += static_cast<std::uint32_t>(in_flight_);
    in_flight_ = 0;
    in_flight_ep_ = 0;
  }

  // ---- control transfers -------------------------------------------------------------------
  void on_setup() {
    ++counters_.setups;
    std::uint8_t bytes[8];
    control_ = Control::idle;  // a SETUP aborts any transfer in progress
    held_set_report_ = false;
    if (hw_.read_out(0, bytes, sizeof bytes) != sizeof bytes) return stall_control();
    setup_ = parse_setup(bytes);
    dispatch();
  }

  void dispatch() {
    using namespace request_type;
    const std::uint8_t type = setup_.bmRequestType & kTypeMask;
    if (type == kStandard) return standard_request();
    if (type == kClass && (setup_.bmRequestType & kRecipientMask) == kInterface &&
        setup_.wIndex == proto::usb::kHidInterface && configured())
      return hid_request();
    if (setup_.bmRequestType == (kDirectionIn | kVendor | kDevice) &&
        setup_.bRequest == kMsOs20VendorCode && setup_.wIndex == kMsOs20DescriptorIndex)
      return reply(ms_os_20_descriptor_set());
    stall_control();
  }

  void standard_request() {
    using namespace request_type;
    const std::uint8_t recipient = setup_.bmRequestType & kRecipientMask;
    const bool in = (setup_.bmRequestType & kDirectionIn) != 0;
    switch (setup_.bRequest) {
      case standard::kGetDescriptor:
        if (!in) break;
        return get_descriptor(recipient);
      case standard::kSetAddress:
        if (in || recipient != kDevice || setup_.wValue > 127 || setup_.wIndex != 0 ||
            setup_.wLength != 0 || state_ == DeviceState::configured)
          break;
        pending_address_ = setup_.wValue;
        return acknowledge();
      case standard::kGetConfiguration:
        if (!in || recipient != kDevice || state_ == DeviceState::default_state) break;
        reply_buf_[0] = configured() ? kConfigurationValue : 0;
        return reply(std::span<const std::uint8_t>(reply_buf_, 1));
      case standard::kSetConfiguration:
        if (in || recipient != kDevice || state_ == DeviceState::default_state ||
            setup_.wLength != 0)
          break;
        if (setup_.wValue == kConfigurationValue) open_stream_endpoints();
        else if (setup_.wValue == 0) unconfigure();
        else break;
        return acknowledge();
      case standard::kGetStatus:
        if (!in) break;
        return get_status(recipient);
      case standard::kClearFeature:
      case standard::kSetFeature:
        if (in || recipient != kEndpoint || setup_.wValue != standard::kEndpointHalt) break;
        return endpoint_halt(setup_.bRequest == standard::kSetFeature);
      case standard::kGetInterface:
        if (!in || recipient != kInterface || !configured() || !interface_exists()) break;
        reply_buf_[0] = 0;
        return reply(std::span<const std::uint8_t>(reply_buf_, 1));
      case standard::kSetInterface:
        if (in || recipient != kInterface || !configured() || !interface_exists() ||
            setup_.wValue != 0)
          break;
        reopen_interface(static_cast<std::uint8_t>(setup_.wIndex));
        return acknowledge();
      default: break;
    }
    stall_control();
  }

  bool interface_exists() const {
    return setup_.wIndex == proto::usb::kVendorInterface ||
           setup_.wIndex == proto::usb::kHidInterface;
  }

  void get_descriptor(std::uint8_t recipient) {
    const auto type = static_cast<std::uint8_t>(setup_.wValue >> 8);
    const auto index = static_cast<std::uint8_t>(setup_.wValue & 0xFF);
    if (recipient == request_type::kDevice) return reply(find_descriptor(type, index, setup_.wIndex));
    // HID class descriptors are asked of the HID interface (facts §2.1)
    if (recipient == request_type::kInterface && setup_.wIndex == proto::usb::kHidInterface &&
        (type == descriptor_type::kHid || type == descriptor_type::kHidReport))
      return reply(find_descriptor(type, index, setup_.wIndex));
    stall_control();
  }

  void get_status(std::uint8_t recipient) {
    reply_buf_[0] = reply_buf_[1] = 0;
    if (state_ == DeviceState::default_state) return stall_control();
    if (recipient == request_type::kDevice) {
      // bit 0 self-powered, as the configuration descriptor's bmAttributes bit 6 says
      const auto config = find_descriptor(descriptor_type::kConfiguration, 0, 0);
      if (config.size() > 7 && (config[7] & 0x40) != 0) reply_buf_[0] = 1;
    } else if (recipient == request_type::kInterface) {
      if (!configured() || !interface_exists()) return stall_control();
    } else if (recipient == request_type::kEndpoint) {
      bool halted = false;
      if (!endpoint_known(setup_.wIndex, halted)) return stall_control();
      reply_buf_[0] = halted ? 1 : 0;
    } else {
      return stall_control();
    }
    reply(std::span<const std::uint8_t>(reply_buf_, 2));
  }

  // Whether wIndex names an endpoint that exists now (ep0 always, the others once configured),
  // and whether it is halted.
  bool endpoint_known(std::uint16_t address, bool& halted) const {
    const std::uint8_t number = address & 0x0F;
    if ((address & ~0x8Fu) != 0) return false;
    if (number == 0) return true;
    if (!configured() || number >= kEndpoints) return false;
    halted = (address & 0x80) ? halted_in_[number] : halted_out_[number];
    return true;
  }

  void endpoint_halt(bool set) {
    bool halted = false;
    if (setup_.wLength != 0 || !endpoint_known(setup_.wIndex, halted)) return stall_control();
    const std::uint8_t number = setup_.wIndex & 0x0F;
    if (number == 0) return set ? stall_control() : acknowledge();  // ep0 never halts
    (setup_.wIndex & 0x80 ? halted_in_ : halted_out_)[number] = set;
    if (set) {
      hw_.stall(number);  // both directions (contract 1)
      if (in_flight_ep_ == number) abandon_in_flight();
      in_busy_[number] = false;
      armed_[number] = false;
    } else {
      reopen_endpoint(number);  // clears the stall, DATA0 both ways
    }
    acknowledge();
  }

  // ---- the control data and status stages ----------------------------------------------------
  // Answers with `data` (truncated to wLength); empty data means "no such thing": STALL.
  void reply(std::span<const std::uint8_t> data) {
    if (data.empty() || (setup_.bmRequestType & request_type::kDirectionIn) == 0)
      return stall_control();
    in_data_ = data.first(std::min<std::size_t>(data.size(), setup_.wLength));
    in_sent_ = 0;
    in_zlp_ = control_in_needs_zlp(in_data_.size(), setup_.wLength);
    control_ = Control::data_in;
    hw_.arm_out(0);  // the status stage, also when the host ends the data stage early
    send_control_packet();
  }

  void send_control_packet() {
    const std::size_t n = std::min(kControlPacketSize, in_data_.size() - in_sent_);
    hw_.write_in(0, in_data_.data() + in_sent_, n);
    in_last_ = n;
  }

  void on_control_in_complete() {
    if (control_ == Control::data_in) {
      in_sent_ += in_last_;
      const bool full = in_last_ == kControlPacketSize;
      if (in_sent_ < in_data_.size()) return send_control_packet();
      if (full && in_zlp_) {
        in_zlp_ = false;
        hw_.write_in(0, nullptr, 0);
        in_last_ = 0;
        return;
      }
      control_ = Control::status_out;  // ep0 OUT is armed since the data stage began
      return;
    }
    if (control_ == Control::status_in) {
      control_ = Control::idle;
      if (pending_address_ >= 0) {
        hw_.set_address(static_cast<std::uint8_t>(pending_address_));
        state_ = pending_address_ == 0 ? DeviceState::default_state : DeviceState::address;
        pending_address_ = -1;
      }
    }
  }

  void on_control_out() {
    if (control_ == Control::data_in || control_ == Control::status_out) {
      control_ = Control::idle;  // the host's status stage (perhaps ending the data early)
      return;
    }
    if (control_ != Control::data_out) return;
    const std::size_t room = sizeof out_buf_ - out_got_;
    const std::size_t n = hw_.read_out(0, out_buf_ + out_got_, room);
    out_got_ += n;
    if (out_got_ < setup_.wLength && n == kControlPacketSize) return hw_.arm_out(0);
    held_set_report_ = true;  // the data stage is over: deliver, then the status stage
    finish_held_set_report();
  }

  // A request without data stage (or whose OUT data is taken): the status stage, a ZLP.
  void acknowledge() {
    control_ = Control::status_in;
    hw_.write_in(0, nullptr, 0);
  }

  void stall_control() {
    ++counters_.control_stalls;
    control_ = Control::idle;
    hw_.stall(0);
  }

  // ---- HID class requests (facts §2.2) -------------------------------------------------------
  void hid_request() {
    const bool in = (setup_.bmRequestType & request_type::kDirectionIn) != 0;
    const auto report_type = static_cast<std::uint8_t>(setup_.wValue >> 8);
    const auto report_id = static_cast<std::uint8_t>(setup_.wValue & 0xFF);
    switch (setup_.bRequest) {
      case hid::kSetIdle:
        if (in || setup_.wLength != 0) break;
        idle_rate_ = static_cast<std::uint8_t>(setup_.wValue >> 8);
        return acknowledge();
      case hid::kGetIdle:
        if (!in) break;
        reply_buf_[0] = idle_rate_;
        return reply(std::span<const std::uint8_t>(reply_buf_, 1));
      case hid::kGetReport:
        if (!in || report_type != hid::kReportTypeInput || report_id != 0) break;
        std::fill(std::begin(reply_buf_), std::end(reply_buf_), std::uint8_t{0});
        return reply(std::span<const std::uint8_t>(reply_buf_, proto::usb::kHidReportSize));
      case hid::kSetReport:
        if (in || report_type != hid::kReportTypeOutput || report_id != 0 ||
            setup_.wLength == 0 || setup_.wLength > sizeof out_buf_)
          break;
        out_got_ = 0;
        control_ = Control::data_out;
        return hw_.arm_out(0);
      default: break;
    }
    stall_control();
  }

  // SET_REPORT's data goes into the receive ring when it has room (beyond what the armed OUT
  // endpoints may still bring); until then the status stage waits (the host is NAKed).
  void finish_held_set_report() {
    if (!held_set_report_ || rx_room_unreserved() < out_got_) return;
    held_set_report_ = false;
    receive(out_buf_, out_got_, kHidEp);
    acknowledge();
  }

  // ---- configuration -------------------------------------------------------------------------
  void open_stream_endpoints() {
    close_stream_endpoints();
    hw_.open_endpoint(kBulkEp, EndpointType::bulk, proto::usb::kBulkPacketSize);
    hw_.open_endpoint(kHidEp, EndpointType::interrupt, proto::usb::kHidReportSize);
    state_ = DeviceState::configured;
    resume_rx();
  }

  void unconfigure() {
    if (configured()) {
      hw_.stall(kBulkEp);  // no stream endpoint answers in the Address state
      hw_.stall(kHidEp);
    }
    close_stream_endpoints();
    state_ = DeviceState::address;
  }

  // SET_INTERFACE: the interface's endpoints start afresh (DATA0, halts cleared).
  void reopen_interface(std::uint8_t interface) {
    const std::uint8_t number = interface == proto::usb::kVendorInterface ? kBulkEp : kHidEp;
    halted_in_[number] = halted_out_[number] = false;
    reopen_endpoint(number);
  }

  // Opens `number` again (DATA0 both ways, stall cleared), keeping a halt still set on its other
  // direction; a packet in flight there is sent again.
  void reopen_endpoint(std::uint8_t number) {
    if (in_flight_ep_ == number) abandon_in_flight();
    in_busy_[number] = false;
    armed_[number] = false;
    hw_.open_endpoint(number, number == kBulkEp ? EndpointType::bulk : EndpointType::interrupt,
                      static_cast<std::uint16_t>(kPacket));
    if (halted_in_[number] || halted_out_[number]) hw_.stall(number);
    if (number == pipe_endpoint()) zlp_owed_ = false;
    resume_rx();
  }

  // ---- the stream: receiving -----------------------------------------------------------------
  void on_stream_out(std::uint8_t number) {
    if (!configured() || number >= kEndpoints || !armed_[number]) {
      ++counters_.ignored_events;
      return;
    }
    armed_[number] = false;
    std::uint8_t packet[kPacket];
    const std::size_t n = hw_.read_out(number, packet, sizeof packet);
    receive(packet, n, number);
    resume_rx();
  }

  void receive(const std::uint8_t* bytes, std::size_t n, std::uint8_t number) {
    rx_.push(bytes, n);  // room was reserved before the endpoint was armed
    counters_.rx_bytes += static_cast<std::uint32_t>(n);
    if (n == 0) return;  // a bulk ZLP: no bytes
    const StreamPipe pipe = number == kBulkEp ? StreamPipe::bulk : StreamPipe::hid;
    if (pipe_ != pipe) {
      if (pipe_ != StreamPipe::none) ++counters_.pipe_switches;
      if (in_flight_ != 0) abandon_in_flight();
      pipe_ = pipe;
      zlp_owed_ = false;
    }
  }

  // Receive-ring room not promised to an armed OUT endpoint.
  std::size_t rx_room_unreserved() const {
    std::size_t armed = 0;
    for (std::size_t n = 1; n < kEndpoints; ++n) armed += armed_[n] ? 1 : 0;
    const std::size_t room = rx_.room();
    return room > armed * kPacket ? room - armed * kPacket : 0;
  }

  // Arms each stream OUT endpoint that is idle, not halted, when a packet's room is free for it;
  // a held SET_REPORT (already received, its host waiting) gets the room first.
  void resume_rx() {
    if (!configured() || held_set_report_) return;
    for (std::uint8_t n = 1; n < kEndpoints; ++n) {
      if (armed_[n] || halted_out_[n] || halted_in_[n]) continue;
      if (rx_room_unreserved() < kPacket) {
        if (!paused_[n]) ++counters_.rx_pauses;
        paused_[n] = true;
        continue;
      }
      paused_[n] = false;
      armed_[n] = true;
      hw_.arm_out(n);
    }
  }

  // ---- the stream: sending -------------------------------------------------------------------
  std::uint8_t pipe_endpoint() const {
    return pipe_ == StreamPipe::bulk ? kBulkEp : pipe_ == StreamPipe::hid ? kHidEp : 0;
  }

  void on_stream_in_complete(std::uint8_t number) {
    if (number >= kEndpoints) {
      ++counters_.ignored_events;
      return;
    }
    in_busy_[number] = false;
    if (in_flight_ep_ != number) return;  // a packet abandoned by a switch: its bytes went again
    tx_.drop(in_flight_);
    counters_.tx_bytes += static_cast<std::uint32_t>(in_flight_);
    zlp_owed_ = number == kBulkEp && in_last_stream_ == kPacket;
    in_flight_ = 0;
    in_flight_ep_ = 0;
  }

  void pump_tx() {
    const std::uint8_t number = pipe_endpoint();
    if (!configured() || number == 0 || in_busy_[number] || in_flight_ != 0 ||
        halted_in_[number] || halted_out_[number])
      return;
    std::uint8_t packet[kPacket];
    const std::size_t take = tx_.peek(0, packet, kPacket);
    std::size_t size = take;
    if (pipe_ == StreamPipe::hid) {
      const std::size_t n = hid_report_take(packet, take);
      if (n == 0) return;
      std::fill(packet + n, packet + kPacket, std::uint8_t{0});
      in_flight_ = n;
      size = kPacket;
    } else {
      if (take == 0 && !zlp_owed_) return;
      zlp_owed_ = false;
      in_flight_ = take;
    }
    in_flight_ep_ = number;
    in_last_stream_ = size;
    in_busy_[number] = true;
    hw_.write_in(number, packet, size);
  }

  H& hw_;
  DeviceState state_ = DeviceState::detached;
  bool suspended_ = false;
  DeviceCounters counters_{};

  // control endpoint
  SetupPacket setup_{};
  Control control_ = Control::idle;
  std::span<const std::uint8_t> in_data_{};  // the IN data stage's bytes
  std::size_t in_sent_ = 0, in_last_ = 0;
  bool in_zlp_ = false;
  int pending_address_ = -1;           // SET_ADDRESS's value until its status stage is sent
  std::uint8_t reply_buf_[proto::usb::kHidReportSize] = {};  // replies built here
  std::uint8_t out_buf_[proto::usb::kHidReportSize] = {};    // SET_REPORT's data stage
  std::size_t out_got_ = 0;
  bool held_set_report_ = false;       // SET_REPORT data waiting for ring room
  std::uint8_t idle_rate_ = 0;         // HID SET_IDLE's duration (4 ms units)

  // stream endpoints, by number (index 0 unused)
  bool armed_[kEndpoints] = {};        // OUT armed (its packet's ring room reserved)
  bool paused_[kEndpoints] = {};       // OUT left un-armed for want of room
  bool in_busy_[kEndpoints] = {};      // an IN packet written, not yet taken
  bool halted_in_[kEndpoints] = {}, halted_out_[kEndpoints] = {};
  StreamPipe pipe_ = StreamPipe::none;
  std::size_t in_flight_ = 0;          // ring bytes in the IN packet not yet taken
  std::uint8_t in_flight_ep_ = 0;
  std::size_t in_last_stream_ = 0;     // size of the last stream IN packet written
  bool zlp_owed_ = false;              // the last bulk packet was full: a ZLP ends the run
  ByteRing<RxCapacity> rx_;
  ByteRing<TxCapacity> tx_;
};

}  // namespace palp::usb
