// SPDX-License-Identifier: Apache-2.0
#include "palp/sim/robot_world.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace palp::sim {

namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;
// A probe axis more than ~80 degrees from the phantom's +z cannot press into its top: the
// plant's mount is then parked out of reach (1 m above the datum).
constexpr double kMinAxisZ = 0.17;
constexpr double kParkedZ_m = -1.0;

plant::Transform phantom_frame_of(const RobotWorldOptions& o) {
  return plant::pose_from_xyzabc(o.phantom_frame_mm[0] * 1e-3, o.phantom_frame_mm[1] * 1e-3,
                                 o.phantom_frame_mm[2] * 1e-3, o.phantom_frame_deg[0] * kRadPerDeg,
                                 o.phantom_frame_deg[1] * kRadPerDeg,
                                 o.phantom_frame_deg[2] * kRadPerDeg);
}

plant::Transform probe_tcp_of(const RobotWorldOptions& o) {
  plant::Transform t;
  for (int i = 0; i < 3; ++i) t.t[i] = o.probe_tcp_mm[i] * 1e-3;
  return t;
}

}  // namespace

plant::Transform RobotWorld::start_flange(const RobotWorldOptions& o) {
  const plant::Transform phantom = phantom_frame_of(o);
  const double tip_phantom[3] = {0, 0, -o.start_above_mm * 1e-3};
  double tip[3];
  proto::rb::apply(phantom, tip_phantom, tip);
  if (o.start_at_tip_mm)
    for (int i = 0; i < 3; ++i) tip[i] = o.start_tip_mm[i] * 1e-3;
  plant::Transform flange;
  flange.r = phantom.r;
  double offset[3];
  proto::rb::rotate(flange.r, probe_tcp_of(o).t, offset);
  for (int i = 0; i < 3; ++i) flange.t[i] = tip[i] - offset[i];
  return flange;
}

RobotWorld::RobotWorld(Simulation& sim, RobotWorldOptions options)
    : sim_(sim),
      options_(options),
      phantom_frame_(phantom_frame_of(options)),
      phantom_inverse_(proto::rb::inverse(phantom_frame_)),
      probe_tcp_(probe_tcp_of(options)),
      arm_(start_flange(options), options.arm),
      bridge_(arm_, options.bridge) {}

void RobotWorld::tip_in_phantom(double out[3]) const {
  const plant::Transform tip = phantom_inverse_ * arm_.flange() * probe_tcp_;
  for (int i = 0; i < 3; ++i) out[i] = tip.t[i];
}

void RobotWorld::tick(double dt_s, plant::Plant& plant, bool contact_line) {
  // the contact line reaches digital input 1 input_latency later (a ring of one level per tick)
  if (line_delay_.empty()) {
    const auto n = static_cast<std::size_t>(std::max(1.0, std::round(options_.input_latency_ms * 1e-3 / dt_s)));
    line_delay_.assign(n, false);
  }
  const bool seen = line_delay_[line_at_];
  line_delay_[line_at_] = contact_line;
  line_at_ = (line_at_ + 1) % line_delay_.size();
  bridge_.set_digital_inputs(seen ? 1u : 0u);

  // the material's force on the tip (against the probe's axis, plus the oblique contact's
  // lateral part), from the phantom frame into the base frame
  const std::array<double, 3> f_phantom = plant.contact_force_vector_N();
  double f[3];
  proto::rb::rotate(phantom_frame_.r, f_phantom.data(), f);
  bridge_.set_external_force(f, true);

  bridge_.advance(dt_s, wall_us_);
  if (!arm_.moving() && placed_) return;  // the mount stays where the arm left it
  double tip[3];
  tip_in_phantom(tip);
  // the probe's axis is the flange's +z; gravity is the base frame's -z
  const std::array<double, 3> axis = probe_axis_in_phantom();
  double down = -arm_.flange().r.m[2][2];
  if (std::abs(1.0 - down) < 1e-12) down = 1.0;  // rounding of a vertical flange
  plant.set_gravity_axis_cosine(std::clamp(down, -1.0, 1.0));
  if (axis[2] >= kMinAxisZ) {
    plant.set_probe_axis(axis);
    plant.move_mount(tip[0], tip[1], tip[2]);
  } else {
    plant.move_mount(tip[0], tip[1], kParkedZ_m);
  }
  placed_ = !arm_.moving();
}

std::array<double, 3> RobotWorld::probe_axis_in_phantom() const {
  const plant::Transform rel = phantom_inverse_ * arm_.flange();
  std::array<double, 3> a = {rel.r.m[0][2], rel.r.m[1][2], rel.r.m[2][2]};
  const double n = std::hypot(a[0], a[1], a[2]);
  for (double& v : a) v /= n;
  return a;
}

ModbusException RobotWorld::read(std::uint16_t address, std::uint16_t count, std::uint16_t* out) {
  return bridge_.read(address, count, out);
}

ModbusException RobotWorld::write(std::uint16_t address, std::span<const std::uint16_t> regs,
                                  bool single) {
  const ModbusException e = bridge_.check_write(address, regs, single);
  if (e != ModbusException::none) return e;
  double at = bridge_.time_s();
  if (bridge_.is_reaction(address, regs)) {
    const std::uint64_t tick = sim_.host_reaction(wall_us_);
    const std::uint64_t now = sim_.ticks();
    if (tick > now)
      at += static_cast<double>(tick - now) / sim_.controller().control_rate_Hz();
  }
  return bridge_.write(address, regs, single, at);
}

}  // namespace palp::sim
