// SPDX-License-Identifier: Apache-2.0
#include "palp/sim/instrument.hpp"

#include <cstdio>
#include <type_traits>

#include "palp/sim/plant_link.hpp"

namespace palp::sim {

Instrument::Instrument(InstrumentOptions options)
    : o_(std::move(options)), phantom_(o_.phantom), seed_(o_.seed) {
  identity_.board = o_.board.c_str();
  identity_.serial = o_.serial.c_str();
  identity_.git_hash = o_.git_hash.c_str();
  identity_.capabilities = (1u << static_cast<unsigned>(proto::Capability::pressure)) |
                           (1u << static_cast<unsigned>(proto::Capability::contact_output)) |
                           (1u << static_cast<unsigned>(proto::Capability::simulated));
  SimulationOptions so;
  so.hold_timeout_ms = o_.hold_timeout_ms;
  so.reaction_latency_ms = o_.reaction_latency_ms;
  sim_ = std::make_unique<Simulation>(identity_, make_plant(o_.phantom, o_.seed), so);
  if (o_.robot) {
    world_ = std::make_unique<RobotWorld>(*sim_, o_.world);
    sim_->set_plant(make_plant(o_.phantom, o_.seed));
    place_on_arm();
  } else {
    mount(o_.mount_mm[0], o_.mount_mm[1], o_.mount_mm[2]);
  }
}

// the plant with the sensor faults between it and the board (sensor_faults.hpp)
std::unique_ptr<PlantLink> Instrument::make_plant(const std::string& phantom, std::uint64_t seed) {
  auto model = std::make_unique<ModelPlant>(phantom, seed);
  const plant::PlantConfig config = model->model().config();
  std::unique_ptr<PlantLink> link;
  if (world_) link = std::make_unique<ArmMountedPlant>(std::move(model), *world_, *sim_);
  else link = std::move(model);
  return std::make_unique<FaultyPlant>(std::move(link), faults_, config.sensors,
                                       config.coil.supply_V);
}

plant::Plant& Instrument::model() {
  PlantLink& link = static_cast<FaultyPlant&>(sim_->plant()).inner();
  if (world_) return static_cast<ArmMountedPlant&>(link).inner().model();
  return static_cast<ModelPlant&>(link).model();
}

void Instrument::mount(double x_mm, double y_mm, double z_mm) {
  mount_mm_ = {x_mm, y_mm, z_mm};
  model().set_mount(x_mm * 1e-3, y_mm * 1e-3, z_mm * 1e-3);
}

// with the robot on, the arm places the probe: the tip where the flange holds it now
void Instrument::place_on_arm() {
  double tip[3];
  world_->tip_in_phantom(tip);
  model().set_mount(tip[0], tip[1], tip[2]);
}

std::string Instrument::rebuild_plant(const std::string& phantom, std::uint64_t seed) {
  try {
    sim_->set_plant(make_plant(phantom, seed));
    phantom_ = phantom;
    seed_ = seed;
    if (world_) place_on_arm();
    else mount(mount_mm_[0], mount_mm_[1], mount_mm_[2]);
    return "ok";
  } catch (const std::exception& e) {
    return std::string("error: ") + e.what();
  }
}

std::string Instrument::control(std::string_view line, Serving& serving) {
  std::string error;
  const auto c = parse_control(line, error);
  if (!c) return "error: " + error;
  return apply(*c, serving);
}

std::string Instrument::status(Serving& serving) {
  char buf[256];
  const auto& c = sim_->counters();
  std::snprintf(buf, sizeof buf,
                "ok virtual_s=%.6f ticks=%llu pace=%g client=%d holding=%d phantom=%s "
                "frames_out=%llu dropped=%llu corrupted=%llu holds=%llu",
                sim_->virtual_s(), static_cast<unsigned long long>(sim_->ticks()), serving.pace(),
                serving.device_client() ? 1 : 0, sim_->holding() ? 1 : 0, phantom_.c_str(),
                static_cast<unsigned long long>(c.frames_out),
                static_cast<unsigned long long>(c.frames_dropped),
                static_cast<unsigned long long>(c.frames_corrupted),
                static_cast<unsigned long long>(c.holds));
  std::string line = buf;
  // what a host-loss test measures: the coil's true current and the latched fault
  std::snprintf(buf, sizeof buf, " coil_A=%.6f fault=%s bootloader_requested=%d",
                model().coil_current_A(), proto::enum_name(sim_->controller().fault()),
                sim_->controller().bootloader_requested() ? 1 : 0);
  line += buf;
  line += serving.status_fields();
  line += " sensor_faults=" + faults_.describe();
  ModbusServer* server = serving.robot_server();
  if (world_ && server) {
    const auto& s = world_->bridge().status();
    const auto& rc = world_->bridge().counters();
    const auto& mc = server->counters();
    double tip[3];
    world_->tip_in_phantom(tip);
    char r[1024];
    std::snprintf(r, sizeof r,
                  " robot_client=%d robot_state=%s robot_x_mm=%.3f robot_y_mm=%.3f "
                  "robot_z_mm=%.3f robot_a_deg=%.3f robot_b_deg=%.3f robot_c_deg=%.3f "
                  "tip_phantom_x_mm=%.3f tip_phantom_y_mm=%.3f tip_phantom_z_mm=%.3f "
                  "robot_ack_seq=%u robot_done_seq=%u robot_result=%s robot_force_mN=%d "
                  "robot_commands=%llu robot_rejected=%llu robot_stops=%llu robot_guards=%llu "
                  "robot_watchdogs=%llu modbus_requests=%llu modbus_exceptions=%llu "
                  "modbus_refused=%llu robot_reply_delay_ms=%g",
                  server->has_client() ? 1 : 0, proto::rb::enum_name(s.state), s.x_um * 1e-3,
                  s.y_um * 1e-3, s.z_um * 1e-3, s.a_mdeg * 1e-3, s.b_mdeg * 1e-3,
                  s.c_mdeg * 1e-3, tip[0] * 1e3, tip[1] * 1e3, tip[2] * 1e3, s.ack_seq,
                  s.done_seq, proto::rb::enum_name(s.result), s.force_mN,
                  static_cast<unsigned long long>(rc.commands),
                  static_cast<unsigned long long>(rc.rejected),
                  static_cast<unsigned long long>(rc.stops),
                  static_cast<unsigned long long>(rc.guards),
                  static_cast<unsigned long long>(rc.watchdogs),
                  static_cast<unsigned long long>(mc.requests),
                  static_cast<unsigned long long>(mc.exceptions),
                  static_cast<unsigned long long>(mc.refused), server->reply_delay_ms());
    line += r;
  }
  return line;
}

std::string Instrument::apply(const ControlCommand& command, Serving& serving) {
  // the robot's knobs need the arm (and some its Modbus server)
  const auto robot_off = [&](const char* name) -> std::string {
    if (world_ && serving.robot_server()) return "";
    return std::string("error: ") + name +
           ": the robot bridge is off (start palp-sim with --robot-port)";
  };
  return std::visit(
      [&](const auto& cmd) -> std::string {
        using C = std::decay_t<decltype(cmd)>;
        if constexpr (std::is_same_v<C, cmd::Help>) {
          return std::string("ok ") + control_help();
        } else if constexpr (std::is_same_v<C, cmd::Status>) {
          return status(serving);
        } else if constexpr (std::is_same_v<C, cmd::Mount>) {
          if (world_)
            return "error: mount: the robot arm places the probe (palp-sim runs with "
                   "--robot-port); move the arm instead";
          mount(cmd.x_mm, cmd.y_mm, cmd.z_mm);
          return "ok";
        } else if constexpr (std::is_same_v<C, cmd::Phantom>) {
          return rebuild_plant(cmd.name, seed_);
        } else if constexpr (std::is_same_v<C, cmd::Seed>) {
          return rebuild_plant(phantom_, cmd.seed);
        } else if constexpr (std::is_same_v<C, cmd::Pace>) {
          const std::string refused = serving.set_pace(cmd.factor);
          return refused.empty() ? "ok" : "error: pace: " + refused;
        } else if constexpr (std::is_same_v<C, cmd::DropFrames>) {
          sim_->options().drop_every = cmd.every;
          return "ok";
        } else if constexpr (std::is_same_v<C, cmd::CorruptFrames>) {
          sim_->options().corrupt_every = cmd.every;
          return "ok";
        } else if constexpr (std::is_same_v<C, cmd::Announce>) {
          fw::DeviceIdentity id = identity_;
          if (!cmd.actual) id.protocol = {cmd.major, cmd.minor, cmd.hash.value_or(proto::kSchemaHash)};
          sim_->controller().set_identity(id);
          return "ok";
        } else if constexpr (std::is_same_v<C, cmd::ReactionLatency>) {
          sim_->options().reaction_latency_ms = cmd.ms;
          return "ok";
        } else if constexpr (std::is_same_v<C, cmd::HoldTimeout>) {
          sim_->options().hold_timeout_ms = cmd.ms;
          return "ok";
        } else if constexpr (std::is_same_v<C, cmd::Fault>) {
          return apply_fault(cmd);
        } else if constexpr (std::is_same_v<C, cmd::RobotReplyDelay>) {
          if (auto off = robot_off("robot-reply-delay"); !off.empty()) return off;
          serving.robot_server()->set_reply_delay_ms(cmd.ms);
          return "ok";
        } else if constexpr (std::is_same_v<C, cmd::RobotDrop>) {
          if (auto off = robot_off("robot-drop"); !off.empty()) return off;
          ModbusServer& server = *serving.robot_server();
          const bool had = server.has_client();
          server.drop_client(*world_);
          return had ? "ok" : "ok no client";
        } else if constexpr (std::is_same_v<C, cmd::RobotFreezeHeartbeat>) {
          if (auto off = robot_off("robot-freeze-heartbeat"); !off.empty()) return off;
          world_->bridge().freeze_heartbeat(cmd.on);
          return "ok";
        } else if constexpr (std::is_same_v<C, cmd::RobotReject>) {
          if (auto off = robot_off("robot-reject"); !off.empty()) return off;
          world_->bridge().reject_next(static_cast<proto::rb::Result>(cmd.result), cmd.count);
          return "ok";
        } else {
          static_assert(std::is_same_v<C, cmd::RobotFault>);
          if (auto off = robot_off("robot-fault"); !off.empty()) return off;
          world_->bridge().inject_fault();
          return "ok";
        }
      },
      command);
}

std::string Instrument::apply_fault(const cmd::Fault& f) {
  using K = cmd::Fault::Kind;
  switch (f.kind) {
    case K::encoder_stuck:
      faults_.encoder_stuck = true;
      faults_.frozen_counts.reset();
      break;
    case K::encoder_glitch:
      faults_.encoder_offset_counts += f.counts;
      faults_.frozen_counts.reset();  // a stuck encoder freezes again where the glitch left it
      break;
    case K::adc_stuck:
      faults_.adc = AdcFault::stuck;
      faults_.frozen_sense_A.reset();
      break;
    case K::adc_saturate:
      faults_.adc = f.high ? AdcFault::saturate_high : AdcFault::saturate_low;
      break;
    case K::driver:
      faults_.driver = true;
      break;
    case K::supply_sag: {
      const double nominal = model().config().coil.supply_V;
      if (f.volts > nominal) {
        char e[128];
        std::snprintf(e, sizeof e,
                      "error: fault supply-sag: %g V is above the nominal supply of %g V", f.volts,
                      nominal);
        return e;
      }
      faults_.supply_V = f.volts;
      break;
    }
    case K::clear:
      faults_.clear();
      break;
  }
  return "ok";
}

}  // namespace palp::sim
