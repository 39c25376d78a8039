// SPDX-License-Identifier: Apache-2.0
// Benchmark image (figures, not a test): the instructions FloatPlant::step() and sensors() cost
// on the Cortex-M4F, counted with SysTick under `qemu-system-arm -icount shift=0` (1 SysTick
// count = 40 instructions, identical on every run; reference/qemu-icount.md).
//
// The coil starts parked, floats at 0.5 A (2.9 V) for 0.5 s (the rise through free air, the
// overshoot into the phantom, the settling), then is pushed at 1.5 A (8.7 V) into the phantom
// for 0.5 s; at 20 kHz and again at 40 kHz. Per phase: mean and max instructions of step() and
// of sensors(). Exit code 0 unless the push failed to indent the phantom (then the contact
// figures would not be contact figures).
#include <cstdint>

#include "console.hpp"
#include "float_plant.hpp"
#include "systick.hpp"

namespace {

using namespace palp;
using palp::fw::dec;

fw::Console console;

struct Cost {
  std::uint64_t total = 0;
  std::uint32_t max = 0, calls = 0;
  void add(std::uint32_t counts) {
    total += counts;
    if (counts > max) max = counts;
    ++calls;
  }
};

std::uint32_t overhead_counts() {
  const std::uint32_t a = board::systick::now();
  const std::uint32_t b = board::systick::now();
  return board::systick::elapsed(a, b);
}

void report(const char* what, const Cost& c) {
  const std::uint32_t k = board::systick::kInstructionsPerCount;
  console << "  " << what << ": mean " << dec(static_cast<std::uint32_t>(c.total * k / c.calls))
          << " instructions, max " << dec(c.max * k) << " (" << dec(c.calls) << " calls)\n";
}

// Runs `ticks` ticks at v_coil_V, adding each step()'s and sensors()' cost.
void run(qemu::FloatPlant& plant, float v_coil_V, float dt_s, std::uint32_t ticks,
         std::uint32_t overhead, Cost& step_cost, Cost& sensor_cost) {
  volatile std::uint16_t sink = 0;
  for (std::uint32_t n = 0; n < ticks; ++n) {
    std::uint32_t a = board::systick::now();
    plant.step(v_coil_V, dt_s);
    std::uint32_t b = board::systick::now();
    std::uint32_t t = board::systick::elapsed(a, b);
    step_cost.add(t > overhead ? t - overhead : 0);
    a = board::systick::now();
    const qemu::PlantSensors s = plant.sensors();
    b = board::systick::now();
    t = board::systick::elapsed(a, b);
    sensor_cost.add(t > overhead ? t - overhead : 0);
    sink = static_cast<std::uint16_t>(sink + s.encoder_timer);
  }
}

}  // namespace

int main() {
  board::systick::start();
  const std::uint32_t overhead = overhead_counts();
  bool indented = true;
  for (const std::uint32_t rate_Hz : {20000u, 40000u}) {
    const float dt = 1.0f / static_cast<float>(rate_Hz);
    qemu::FloatPlant plant;
    Cost float_step, float_sensors, push_step, push_sensors;
    run(plant, 2.9f, dt, rate_Hz / 2, overhead, float_step, float_sensors);
    run(plant, 8.7f, dt, rate_Hz / 2, overhead, push_step, push_sensors);
    const auto depth_um = static_cast<std::uint32_t>(plant.indentation_m() * 1e6f);
    indented = indented && depth_um > 1000;
    console << "float plant on cortex-m4 (qemu -icount shift=0), " << dec(rate_Hz / 1000)
            << " kHz; after the push: depth " << dec(depth_um) << " um\n";
    report("step, parked -> floating at 0.5 A (free air and contact)", float_step);
    report("sensors, same phase", float_sensors);
    report("step, pushed at 1.5 A (in contact)", push_step);
    report("sensors, same phase", push_sensors);
  }
  return indented ? 0 : 1;
}
