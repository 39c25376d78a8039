// SPDX-License-Identifier: Apache-2.0
// USB device core cost image: the instructions firmware/usb's Device<H> (device.hpp) spends per
// 64-byte bulk packet in each direction, counted with SysTick under `qemu-system-arm -icount
// shift=0` (1 SysTick count = 40 instructions, identical on every run; reference/qemu-icount.md),
// and what full-speed bulk at its most (19 packets of 64 bytes per 1 ms frame, usb.hpp
// kBulkBytesPerS, in both directions at once) costs a 170 MHz STM32G474 at an assumed 1.3 cycles
// per instruction.
//
// The hardware is a stub with the contract's calls (hardware.hpp) that copies packets byte by
// byte, standing in for the FSDEV driver's PMA copies; the driver's register accesses are not
// in these figures. Counted per packet:
//   IN   the host takes a packet (an in_complete event), service() drops its bytes and writes the
//        next one; the app's write() of 64 bytes is counted apart;
//   OUT  a packet arrives (an out event), service() moves it into the ring and re-arms; the
//        app's read() of 64 bytes is counted apart.
// The budget (exit 1 when broken, so ctest fails): the stream direction at the most bulk carries
// (19 IN packets per ms) with one OUT packet per ms (1000 commands/s, far more than the SDK
// sends), service() and the app's calls together, take at most 10 % of the CPU: half of the 20 %
// firmware/tests/tick_cost_main.cpp leaves beside the control tick and the main loop. Printed
// too: both ways at 19 packets/ms (a load the protocol never makes), and the wire rate of the
// densest streams, all channels at the core's ceiling (fw::Streamer::kMaxRate_Hz, 20 kHz) and
// every tick at 40 kHz, against what full-speed bulk carries.
#include <cstddef>
#include <cstdint>

#include "console.hpp"
#include "palp/fw/streamer.hpp"
#include "palp/protocol/stream.hpp"
#include "palp/protocol/usb.hpp"
#include "palp/usb/device.hpp"
#include "instruction_count.hpp"

namespace {

using namespace palp;
using palp::fw::dec;

fw::Console console;

constexpr std::uint32_t kPartHz = 170'000'000;  // STM32G474
constexpr std::uint32_t kCpiTimes10 = 13;       // assumed 1.3 cycles/instruction
constexpr std::uint32_t kBudgetPercent = 10;
constexpr std::uint32_t kPacketsPerMs = proto::usb::kBulkBytesPerS / 1000 / 64;  // 19
constexpr std::uint32_t kPackets = 512;  // per measurement

// Contract 1 with one-packet buffers per endpoint and an event queue the "host" fills.
class StubHardware {
 public:
  usb::Event poll() {
    if (head_ == tail_) return {};
    return events_[tail_++ % kQueue];
  }
  void open_endpoint(std::uint8_t, usb::EndpointType, std::uint16_t) {}
  std::size_t read_out(std::uint8_t number, std::uint8_t* bytes, std::size_t capacity) {
    const std::size_t n = out_size_[number] < capacity ? out_size_[number] : capacity;
    for (std::size_t k = 0; k < n; ++k) bytes[k] = out_[number][k];
    return n;
  }
  void arm_out(std::uint8_t number) { armed_[number] = true; }
  void write_in(std::uint8_t number, const std::uint8_t* bytes, std::size_t size) {
    for (std::size_t k = 0; k < size; ++k) in_[number][k] = bytes[k];
    in_size_[number] = size;
    in_pending_[number] = true;
  }
  void stall(std::uint8_t) {}
  void set_address(std::uint8_t) {}
  void connect(bool) {}

  // the host's side
  void push(usb::EventKind kind, std::uint8_t number) { events_[head_++ % kQueue] = {kind, number}; }
  void setup(const std::uint8_t (&bytes)[8]) {
    for (std::size_t k = 0; k < 8; ++k) out_[0][k] = bytes[k];
    out_size_[0] = 8;
    in_pending_[0] = false;
    push(usb::EventKind::setup, 0);
  }
  /// The host takes the IN packet waiting on `number`, if any.
  bool take_in(std::uint8_t number) {
    if (!in_pending_[number]) return false;
    in_pending_[number] = false;
    push(usb::EventKind::in_complete, number);
    return true;
  }
  /// The host sends `size` bytes to `number` when it is armed.
  bool send_out(std::uint8_t number, std::size_t size) {
    if (!armed_[number]) return false;
    armed_[number] = false;
    for (std::size_t k = 0; k < size; ++k) out_[number][k] = static_cast<std::uint8_t>(k + 1);
    out_size_[number] = size;
    push(usb::EventKind::out, number);
    return true;
  }
  std::size_t in_size(std::uint8_t number) const { return in_size_[number]; }

 private:
  static constexpr std::uint32_t kQueue = 16;
  usb::Event events_[kQueue] = {};
  std::uint32_t head_ = 0, tail_ = 0;
  std::uint8_t out_[3][64] = {}, in_[3][64] = {};
  std::size_t out_size_[3] = {}, in_size_[3] = {};
  bool armed_[3] = {}, in_pending_[3] = {};
};

StubHardware hw;
usb::Device<StubHardware> device{hw};

using cost::barrier;
using cost::instructions_of;

// A control request without data stage, answered: SETUP, then the host takes the status ZLP.
void control(std::uint8_t type, std::uint8_t request, std::uint8_t value) {
  const std::uint8_t setup[8] = {type, request, value, 0, 0, 0, 0, 0};
  hw.setup(setup);
  device.service();
  hw.take_in(0);
  device.service();
}

}  // namespace

int main() {
  cost::start_counting();
  console << "usb device core on cortex-m4 (qemu -icount shift=0, 1 SysTick count = 40 "
             "instructions), stub hardware copying bytes:\n";

  // Attach, SET_ADDRESS(5), SET_CONFIGURATION(1), and one OUT byte on bulk (the host talks first)
  device.start();
  hw.push(usb::EventKind::reset, 0);
  device.service();
  control(0x00, 0x05, 5);
  control(0x00, 0x09, 1);
  std::uint8_t app[64];
  hw.send_out(1, 1);
  device.service();
  device.read(app, sizeof app);
  bool ok = device.configured() && device.sending_pipe() == usb::StreamPipe::bulk;

  // Bulk IN: the ring kept full by the app, the host taking packet after packet
  for (std::size_t k = 0; k < sizeof app; ++k) app[k] = static_cast<std::uint8_t>(k | 1);
  while (device.write(app, sizeof app) == sizeof app) {
  }
  device.service();  // the first packet
  std::uint32_t in_service = 0, in_app = 0, in_full = 0;
  for (std::uint32_t p = 0; p < kPackets; ++p) {
    if (!hw.take_in(1)) ok = false;
    in_service += instructions_of([] { device.service(); });
    in_app += instructions_of([&] { device.write(app, sizeof app); });
    in_full += hw.in_size(1) == 64 ? 1 : 0;
  }
  ok = ok && in_full == kPackets;

  // Bulk OUT: a full packet at a time, the app reading 64 bytes after each
  std::uint32_t out_service = 0, out_app = 0, out_bytes = 0;
  for (std::uint32_t p = 0; p < kPackets; ++p) {
    if (!hw.send_out(1, 64)) ok = false;
    out_service += instructions_of([] { device.service(); });
    out_app += instructions_of([&] { out_bytes += device.read(app, sizeof app); });
  }
  ok = ok && out_bytes == kPackets * 64;

  const std::uint32_t in_per = (in_service + in_app) / kPackets;
  const std::uint32_t out_per = (out_service + out_app) / kPackets;
  console << "bulk IN:  service() " << dec(in_service / kPackets) << " + app write() "
          << dec(in_app / kPackets) << " instructions per 64-byte packet\n";
  console << "bulk OUT: service() " << dec(out_service / kPackets) << " + app read() "
          << dec(out_app / kPackets) << " instructions per 64-byte packet\n";
  // tenths of a percent of the part for in_pkts IN and out_pkts OUT packets per ms
  const auto permille_of = [&](std::uint32_t in_pkts, std::uint32_t out_pkts) {
    const std::uint64_t cycles_per_s =
        (static_cast<std::uint64_t>(in_per) * in_pkts + static_cast<std::uint64_t>(out_per) * out_pkts) *
        1000 * kCpiTimes10 / 10;
    return static_cast<std::uint32_t>(cycles_per_s * 1000 / kPartHz);
  };
  const auto share = [](std::uint32_t permille) {
    console << dec(permille / 10) << '.' << dec(permille % 10) << " %";
  };
  const std::uint32_t both = permille_of(kPacketsPerMs, kPacketsPerMs);
  const std::uint32_t stream = permille_of(kPacketsPerMs, 1);
  console << "of a 170 MHz part at 1.3 cycles/instruction: both ways at " << dec(kPacketsPerMs)
          << " packets/ms ";
  share(both);
  console << "; the stream direction at " << dec(kPacketsPerMs) << " packets/ms with 1 OUT/ms ";
  share(stream);
  console << "\n";
  const auto core_bytes_per_s = static_cast<std::uint32_t>(
      static_cast<std::uint64_t>(kPartHz) * 10 / kCpiTimes10 * 64 / (in_per > 0 ? in_per : 1));
  console << "the core alone could send " << dec(core_bytes_per_s) << " bytes/s; USB FS bulk "
          << "carries " << dec(proto::usb::kBulkBytesPerS) << "\n";
  // The streams the question is about: all channels at the core's ceiling (every tick at the
  // default 20 kHz control rate), and every tick at 40 kHz, which the core refuses.
  constexpr std::size_t kBatch = proto::max_batch_samples(proto::kAllChannels);
  const auto densest = [&](std::uint32_t rate_Hz, const char* what) {
    const std::uint32_t bytes =
        proto::stream_wire_bytes_per_s(proto::kAllChannels, static_cast<double>(rate_Hz), kBatch);
    const auto of_bulk = static_cast<std::uint32_t>(std::uint64_t{bytes} * 1000 /
                                                    proto::usb::kBulkBytesPerS);
    console << "all channels at " << dec(rate_Hz / 1000) << " kHz in batches of " << dec(kBatch)
            << " (" << what << "): " << dec(bytes) << " bytes/s on the wire, ";
    share(of_bulk);
    console << " of full-speed bulk, ";
    share(permille_of((bytes + 63) / 64 / 1000 + 1, 1));
    console << " of the part here\n";
  };
  densest(fw::Streamer::kMaxRate_Hz, "the core's ceiling, fw::Streamer::kMaxRate_Hz");
  densest(40000, "every tick at 40 kHz, refused by the core");
  const bool within = ok && stream <= kBudgetPercent * 10;
  console << "usb budget (" << dec(kBudgetPercent) << " %, the stream direction): "
          << (within ? "within budget" : ok ? "OVER BUDGET" : "DID NOT RUN") << '\n';
  return within ? 0 : 1;
}
