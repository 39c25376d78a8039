// palp-sim's speed on one core: the firmware core and the physical model together, per control
// tick, while a program runs and all channels stream at 10 kHz (the host side only drains bytes).
// Prints ns per tick and the real-time factor (simulated seconds per wall second) at 20 and 40 kHz.
#include <benchmark/benchmark.h>

#include <memory>

#include "palp/sim/plant_link.hpp"
#include "palp/sim/simulation.hpp"

namespace {

using namespace palp;

template <class M>
void send(sim::Simulation& s, const M& m, proto::u16 seq, std::uint64_t wall_us = 0) {
  std::vector<proto::u8> w(proto::kMaxWireFrame);
  w.resize(proto::encode_message(m, seq, 0, w.data(), w.size()));
  s.host_bytes(w.data(), w.size(), wall_us);
}

void BM_SimulationTick(benchmark::State& state) {
  const auto rate_Hz = static_cast<std::uint32_t>(state.range(0));
  const bool multisine = state.range(1) != 0;
  fw::DeviceIdentity id;
  id.board = "palp-sim";
  sim::Simulation s(id, std::make_unique<sim::ModelPlant>("solid_1d", 1));
  auto& plant = static_cast<sim::ModelPlant&>(s.plant()).model();
  plant.set_mount(0.0, 0.0, 0.0);
  proto::SetParams p;
  p.control_rate_Hz = rate_Hz;
  send(s, p, 1);
  send(s, proto::StreamConfigure{proto::kAllChannels, static_cast<proto::u16>(rate_Hz / 10000), 40}, 2);
  send(s, proto::StreamStart{}, 3);
  if (multisine) {
    proto::LoadMultisine m;
    m.line_first = 1;
    m.line_last = 400;
    m.line_step = 1;
    m.fundamental_Hz = 0.25f;
    m.line_amplitude_A = 0.0005f;
    m.periods = 0;
    send(s, m, 4);
  } else {
    send(s, proto::LoadHold{0.6f, 0.0f}, 4);
  }
  send(s, proto::ProgramStart{}, 5);
  std::uint64_t ticks = 0;
  std::uint64_t wall = 0;
  for (auto _ : state) {
    // 1 ms of virtual time per iteration, with a heartbeat so the watchdog stays fed
    ticks += s.run(rate_Hz / 1000, wall);
    wall += 1000;
    send(s, proto::Heartbeat{}, 6, wall);
    benchmark::DoNotOptimize(s.take_device_bytes());
  }
  state.counters["ns_per_tick"] = benchmark::Counter(
      static_cast<double>(ticks), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["realtime_factor"] =
      benchmark::Counter(static_cast<double>(ticks) / rate_Hz, benchmark::Counter::kIsRate);
  if (s.controller().faulted()) {
    static std::string why;
    why = "the controller faulted: reason " +
          std::to_string(static_cast<int>(s.controller().fault()));
    state.SkipWithError(why.c_str());
  }
}

BENCHMARK(BM_SimulationTick)
    ->ArgNames({"rate_Hz", "multisine"})
    ->Args({20000, 0})
    ->Args({20000, 1})
    ->Args({40000, 0})
    ->Args({40000, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
