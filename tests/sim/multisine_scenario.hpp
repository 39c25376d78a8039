// SPDX-License-Identifier: Apache-2.0
// The load palp-sim's speed is measured under (bench_sim) and its output pinned by (sim_reference_
// tests), issue 16: a Simulation on a phantom with the coil 25 mm out of the surface at a site, every
// channel streamed at 10 kHz, and a 400-line multisine (0.25 Hz fundamental, 0.5 mA a line) about
// a 1.0 A bias, so the probe is in contact. One definition for both.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "palp/protocol/frame.hpp"
#include "palp/protocol/messages.hpp"
#include "palp/sim/plant_link.hpp"
#include "palp/sim/simulation.hpp"

namespace palp::sim::test {

/// Encodes m as one frame and hands it to the simulation as host bytes at wall_us.
template <class M>
void send_frame(Simulation& s, const M& m, proto::u16 seq, std::uint64_t wall_us = 0) {
  std::vector<proto::u8> w(proto::kMaxWireFrame);
  w.resize(proto::encode_message(m, seq, 0, w.data(), w.size()));
  s.host_bytes(w.data(), w.size(), wall_us);
}

/// A simulation of the phantom (seed) with the floating coil's tip 25 mm above the surface at
/// (x_m, y_m): the 1.0 A bias presses it in.
inline std::unique_ptr<Simulation> make_scenario_simulation(const char* phantom, double x_m,
                                                            double y_m, std::uint64_t seed) {
  fw::DeviceIdentity id;
  id.board = "palp-sim";
  auto s = std::make_unique<Simulation>(id, std::make_unique<ModelPlant>(phantom, seed));
  auto& plant = static_cast<ModelPlant&>(s->plant()).model();
  plant.set_mount(x_m, y_m, plant.phantom()->surface_z_m(x_m, y_m) - 0.025);
  return s;
}

/// The requests (seq 0..5) that open the session (Hello), set the control rate, stream every
/// channel at 10 kHz and start the 400-line multisine about 1.0 A, as host bytes at wall_us.
inline void start_multisine_scenario(Simulation& s, std::uint32_t rate_Hz,
                                     std::uint64_t wall_us = 0) {
  send_frame(s, proto::Hello{proto::kProtocolMajor, proto::kProtocolMinor, proto::kSchemaHash, "scenario"},
             0, wall_us);
  proto::SetParams p;
  p.control_rate_Hz = rate_Hz;
  send_frame(s, p, 1, wall_us);
  send_frame(s, proto::StreamConfigure{proto::kAllChannels, static_cast<proto::u16>(rate_Hz / 10000), 40},
             2, wall_us);
  send_frame(s, proto::StreamStart{}, 3, wall_us);
  proto::LoadMultisine m;
  m.line_first = 1;
  m.line_last = 400;
  m.line_step = 1;
  m.fundamental_Hz = 0.25f;
  m.line_amplitude_A = 0.0005f;
  m.offset_A = 1.0f;
  m.periods = 0;
  send_frame(s, m, 4, wall_us);
  send_frame(s, proto::ProgramStart{}, 5, wall_us);
}

}  // namespace palp::sim::test
