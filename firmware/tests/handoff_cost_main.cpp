// SPDX-License-Identifier: Apache-2.0
// Benchmark image: how long receive() holds the tick guard (Controller::set_tick_guard), i.e. how
// late a control tick can start because a command is being handed over, counted with SysTick
// under `qemu-system-arm -icount shift=0` (1 SysTick count = 40 instructions;
// reference/qemu-icount.md).
//
// The guard's hold() and release() read SysTick; every request type is sent through the real
// Controller in its costliest form (a 400-line Schroeder multisine, the paper's ramp and sweep,
// control-rate changes that reconfigure the stream, a full calibration, a running program and
// stream for the busy refusals) and the image prints, per request, the longest held section and
// the whole receive() call (decoding, synthesis and the reply's encoding included). Last line:
// the longest held section of all and its share of a 40 kHz tick at 170 MHz and an assumed 1.3
// cycles per instruction; "within budget" when it is at most kBudgetInstructions (exit 0), else
// "OVER BUDGET" (exit 1).
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

constexpr std::uint32_t kCyclesPerTick40k = 170'000'000 / 40'000;  // 4250
constexpr std::uint32_t kCpiTimes10 = 13;  // assumed 1.3 cycles/instruction
// A held section delays the tick it overlaps; a quarter of a 40 kHz tick (~1060 cycles of
// 4250) leaves the tick (56 % of its period) room to finish before the next one falls due.
constexpr std::uint32_t kBudgetInstructions = kCyclesPerTick40k * 10 / kCpiTimes10 / 4;  // 817

struct Held {
  std::uint32_t overhead = 0;   // a now() pair's own cost, subtracted
  std::uint32_t started = 0;
  std::uint32_t max_counts = 0;  // this request's longest section
  std::uint32_t sections = 0;
} held;

void on_hold(void*) {
  ++held.sections;
  held.started = board::systick::now();
}
void on_release(void*) {
  std::uint32_t t = board::systick::elapsed(held.started, board::systick::now());
  t = t > held.overhead ? t - held.overhead : 0;
  if (t > held.max_counts) held.max_counts = t;
}

std::uint32_t instructions(std::uint32_t counts) {
  return counts * board::systick::kInstructionsPerCount;
}

const char* worst_name = "";
std::uint32_t worst_counts = 0;
std::uint64_t wd_us = 1'000'000;
std::uint16_t seq = 0;
proto::u8 sink[2048];

// Sends m, prints its longest held section and its whole receive() cost.
template <class M>
void measure(const char* what, const M& m) {
  static proto::u8 wire[proto::kMaxWireFrame];
  const std::size_t n = proto::encode_message(m, seq++, 0, wire, sizeof wire);
  held.max_counts = 0;
  held.sections = 0;
  const std::uint32_t a = board::systick::now();
  controller.receive(wire, n, wd_us);
  const std::uint32_t total = board::systick::elapsed(a, board::systick::now());
  console << what << ": held max " << dec(instructions(held.max_counts)) << " instructions in "
          << dec(held.sections) << " section(s); receive() " << dec(instructions(total)) << '\n';
  if (held.max_counts > worst_counts) {
    worst_counts = held.max_counts;
    worst_name = what;
  }
  controller.service();
  while (controller.transmit(sink, sizeof sink) > 0) {
  }
}

// The coil's current one tick later under this voltage (R = 5.8 ohm, L = 2.07 mH, exact over
// 50 us): a live current-sense reading, which the sensor checks require.
float coil_current_after(float i_A, float v_V) {
  constexpr float a = 0.869274243f;  // exp(-R dt / L)
  return i_A * a + v_V * ((1.0f - a) / 5.8f);
}

// A few ticks between requests, as the interrupt would run them.
void ticks(int count) {
  static fw::TickInputs in;
  in.pressure_codes.fill(2048);
  for (int k = 0; k < count; ++k) {
    fw::TickOutputs out;
    in.watchdog_now_us = wd_us;
    controller.tick(in, out);
    in.i_sense_A = coil_current_after(in.i_sense_A, out.v_coil_V);
    wd_us += 50;
  }
}

proto::LoadMultisine four_hundred_lines() {
  proto::LoadMultisine ms;  // 400 lines, 0.25 ... 100 Hz: the costliest synthesis
  ms.offset_A = 0.2f;
  ms.fundamental_Hz = 0.25f;
  ms.line_first = 1;
  ms.line_last = 400;
  ms.line_step = 1;
  ms.line_amplitude_A = 0.0005f;
  ms.phase_mode = proto::PhaseMode::schroeder;
  ms.periods = 0;
  return ms;
}

}  // namespace

int main() {
  board::systick::start();
  {
    const std::uint32_t a = board::systick::now();
    const std::uint32_t b = board::systick::now();
    held.overhead = board::systick::elapsed(a, b);
  }
  controller.set_tick_guard(fw::TickGuard{&on_hold, &on_release, nullptr});
  console << "tick guard on cortex-m4 (qemu -icount shift=0, 1 SysTick count = 40 instructions): "
             "the longest held section per request, and the whole receive()\n";

  measure("Hello", proto::Hello{proto::kProtocolMajor, proto::kProtocolMinor, proto::kSchemaHash,
                                "handoff-cost"});
  measure("GetDeviceInfo", proto::GetDeviceInfo{});
  measure("Ping", proto::Ping{1, 2});
  measure("Heartbeat", proto::Heartbeat{});
  measure("GetParams", proto::GetParams{});
  proto::SetParams p;
  p.control_rate_Hz = 40000;  // reconfigures the stream for the new rate
  measure("SetParams (20 -> 40 kHz)", p);
  p.control_rate_Hz = 20000;
  measure("SetParams (40 -> 20 kHz)", p);
  auto cal = proto::fields_as<proto::SetCalibration>(fw::to_proto(fw::CalibrationData{}));
  cal.kf_position_counts = {};  // a four-point force-constant table instead of the default's one
  cal.kf_N_per_A = {};
  for (std::int32_t x : {0, 9000, 21000, 34000}) cal.kf_position_counts.push_back(x);
  for (float k : {3.84f, 3.6f, 3.2f, 2.918f}) cal.kf_N_per_A.push_back(k);
  measure("SetCalibration", cal);
  measure("GetCalibration", proto::GetCalibration{});
  measure("CommitCalibration", proto::CommitCalibration{});
  proto::LoadRamp ramp;  // the paper's 2D ramp: 251 levels
  ramp.start_A = 0.5f;
  ramp.stop_A = 3.0f;
  ramp.step_A = 0.01f;
  ramp.dwell_s = 0.025f;
  ramp.repetitions = 3;
  ramp.unload = 1;
  measure("LoadRamp", ramp);
  measure("LoadSweep", proto::LoadSweep{});
  measure("LoadMultisine (400 lines)", four_hundred_lines());
  measure("StreamConfigure", proto::StreamConfigure{proto::kAllChannels, 2, 40});
  measure("StreamStart", proto::StreamStart{});
  measure("ProgramStart", proto::ProgramStart{});
  ticks(100);
  measure("GetStatus", proto::GetStatus{});
  measure("GetHealth", proto::GetHealth{});
  measure("GetProgramStatus", proto::GetProgramStatus{});
  measure("LoadMultisine while running (busy)", four_hundred_lines());
  measure("SetParams while running (busy)", p);
  measure("EnterBootloader while running (busy)", proto::EnterBootloader{0x544F4F42u});
  ticks(100);
  measure("ProgramStop", proto::ProgramStop{});
  measure("StreamStop", proto::StreamStop{});
  measure("FaultClear", proto::FaultClear{});

  const std::uint32_t worst = instructions(worst_counts);
  const std::uint32_t share = worst * kCpiTimes10 * 100 / kCyclesPerTick40k;  // tenths of a %
  const bool ok = worst <= kBudgetInstructions && !controller.faulted();
  console << "longest held section: " << dec(worst) << " instructions (" << worst_name
          << "); at 1.3 cycles/instruction " << dec(share / 10) << '.' << dec(share % 10)
          << " % of a 40 kHz tick at 170 MHz; budget " << dec(kBudgetInstructions)
          << " instructions: " << (ok ? "within budget" : "OVER BUDGET") << '\n';
  return ok ? 0 : 1;
}
