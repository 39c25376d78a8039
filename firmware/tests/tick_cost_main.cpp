// Benchmark image (figures, not a test): the instructions the firmware core spends per control
// tick in its worst case — a 400-line multisine running while all 11 channels stream at 10 kHz —
// counted with SysTick under `qemu-system-arm -icount shift=0` (1 SysTick count = 40
// instructions, identical on every run; reference/qemu-icount.md).
//
// It drives the real Controller through the protocol (Hello, LoadMultisine, StreamConfigure,
// StreamStart, ProgramStart), runs 4000 ticks (0.2 s at 20 kHz) and prints per-tick figures for
// tick() and for the main loop's service() + transmit(), and their share of a 170 MHz, 20 kHz
// tick (8500 cycles) at an assumed 1.3 cycles per instruction (qemu-icount.md: 1.1-1.5 on such
// code; instruction counts are a lower bound on cycles).
#include <cstdint>

#include "console.hpp"
#include "palp/fw/controller.hpp"
#include "systick.hpp"

namespace {

using namespace palp;
using palp::fw::dec;

fw::Console console;
fw::Controller controller{fw::DeviceIdentity{"qemu-mps2", "QEMU-0", "", 0, 1, 0, 0,
                                             proto::kThisProtocol}};

constexpr std::uint32_t kTicks = 4000;
constexpr std::uint32_t kCyclesPerTick = 170'000'000 / 20'000;  // 8500
constexpr std::uint32_t kCpiTimes10 = 13;                       // assumed 1.3 cycles/instruction

template <class M>
void send(const M& m, std::uint16_t seq, std::uint64_t wd_us) {
  static proto::u8 wire[proto::kMaxWireFrame];
  const std::size_t n = proto::encode_message(m, seq, 0, wire, sizeof wire);
  controller.receive(wire, n, wd_us);
}

std::uint32_t instructions(std::uint32_t counts) {
  return counts * board::systick::kInstructionsPerCount;
}

// Mean and max instructions per call, and their share of `ticks` control ticks' cycle budget.
void report(const char* what, std::uint64_t total_counts, std::uint32_t max_counts,
            std::uint32_t calls, std::uint32_t ticks) {
  const std::uint32_t per = calls;
  const std::uint32_t mean = instructions(static_cast<std::uint32_t>(total_counts / per));
  const std::uint32_t peak = instructions(max_counts);
  // share of the tick budget at the assumed CPI, in tenths of a percent
  const std::uint32_t share_mean = mean * kCpiTimes10 * 100 / (kCyclesPerTick * ticks);
  const std::uint32_t share_peak = peak * kCpiTimes10 * 100 / (kCyclesPerTick * ticks);
  console << what << ": mean " << dec(mean) << " instructions, max " << dec(peak)
          << "; at 1.3 cycles/instruction " << dec(share_mean / 10) << '.' << dec(share_mean % 10)
          << " % (max " << dec(share_peak / 10) << '.' << dec(share_peak % 10)
          << " %) of " << dec(ticks) << " tick(s) at 170 MHz, 20 kHz\n";
}

// The coil's current one tick later under this voltage (R = 5.8 ohm, L = 2.07 mH, exact over
// 50 us): the current-sense reading of a live coil, which the sensor checks require (a reading
// frozen while the loop swings the voltage is a current_sense_error).
float coil_current_after(float i_A, float v_V) {
  constexpr float a = 0.869274243f;  // exp(-R dt / L)
  return i_A * a + v_V * ((1.0f - a) / 5.8f);
}

}  // namespace

int main() {
  std::uint64_t wd_us = 1'000'000;
  proto::LoadMultisine ms;  // 400 lines, 0.25 Hz .. 100 Hz
  ms.offset_A = 1.0f;
  ms.fundamental_Hz = 0.25f;
  ms.line_first = 1;
  ms.line_last = 400;
  ms.line_step = 1;
  ms.line_amplitude_A = 0.0005f;
  ms.phase_mode = proto::PhaseMode::random_seeded;
  ms.periods = 0;
  send(proto::Hello{proto::kProtocolMajor, proto::kProtocolMinor, proto::kSchemaHash, "tick-cost"}, 0,
       wd_us);  // the session: nothing but identify and bootloader is served before it
  send(ms, 1, wd_us);
  send(proto::StreamConfigure{proto::kAllChannels, 2, 40}, 2, wd_us);
  send(proto::StreamStart{}, 3, wd_us);
  send(proto::ProgramStart{}, 4, wd_us);
  static proto::u8 sink[2048];
  controller.service();
  while (controller.transmit(sink, sizeof sink) > 0) {
  }

  // the cost of the measurement itself, subtracted from every reading
  board::systick::start();
  std::uint32_t a = board::systick::now();
  std::uint32_t b = board::systick::now();
  const std::uint32_t overhead = board::systick::elapsed(a, b);

  std::uint64_t tick_total = 0, service_total = 0;
  std::uint32_t tick_max = 0, service_max = 0, services = 0;
  fw::TickInputs in;
  in.pressure_codes.fill(2048);
  for (std::uint32_t k = 0; k < kTicks; ++k) {
    fw::TickOutputs out;
    in.watchdog_now_us = wd_us;
    a = board::systick::now();
    controller.tick(in, out);
    b = board::systick::now();
    std::uint32_t t = board::systick::elapsed(a, b);
    t = t > overhead ? t - overhead : 0;
    tick_total += t;
    if (t > tick_max) tick_max = t;
    in.i_sense_A = coil_current_after(in.i_sense_A, out.v_coil_V);
    wd_us += 50;
    if (k % 8 == 7) {  // the main loop every 8 ticks: batches, events, transmit
      a = board::systick::now();
      controller.service();
      while (controller.transmit(sink, sizeof sink) > 0) {
      }
      b = board::systick::now();
      t = board::systick::elapsed(a, b);
      t = t > overhead ? t - overhead : 0;
      service_total += t;
      if (t > service_max) service_max = t;
      ++services;
    }
  }
  const proto::Health h = controller.health();
  console << "tick cost on cortex-m4 (qemu -icount shift=0, 1 SysTick count = 40 instructions): "
          << dec(kTicks) << " ticks of a 400-line multisine with 11 channels streamed at 10 kHz\n";
  report("control tick", tick_total, tick_max, kTicks, 1);
  report("main loop (service + transmit, every 8 ticks)", service_total, service_max, services, 8);
  console << "frames sent " << dec(h.frames_tx) << ", samples lost "
          << dec(h.isr_queue_overflows + h.stream_samples_lost) << ", faults "
          << dec(controller.faulted() ? 1 : 0) << '\n';
  // the figures are the worst case only if the requests were served: 2000 samples in 50 batches
  const bool streamed = h.frames_tx >= kTicks / 2 / 40;
  if (!streamed) console << "the stream did not run: a request was refused\n";
  return controller.faulted() || !streamed ? 1 : 0;
}
