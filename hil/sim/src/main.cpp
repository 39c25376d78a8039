// palp-sim: the probe controller's firmware core and the physical model in virtual time, served
// over a loopback socket with the device protocol, plus a control channel for the simulator's
// own knobs, and with --robot-port the KUKA robot bridge (Modbus TCP) carrying the probe
// (hil/README.md).
#include <CLI/CLI.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "palp/plant/phantom.hpp"
#include "palp/sim/byte_server.hpp"
#include "palp/sim/control.hpp"
#include "palp/sim/modbus_server.hpp"
#include "palp/sim/plant_link.hpp"
#include "palp/sim/robot_world.hpp"
#include "palp/sim/simulation.hpp"

namespace {

using namespace palp;
using Clock = std::chrono::steady_clock;

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

std::uint64_t wall_us(Clock::time_point t0) {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - t0).count());
}

struct Options {
  std::string listen = "127.0.0.1";
  std::uint16_t port = 7070;
  std::string unix_path;
  std::uint16_t control_port = 7071;
  std::string phantom = "none";
  std::vector<double> mount_mm{0.0, 0.0, 0.0};
  std::uint64_t seed = 1;
  std::string pace = "realtime";
  double hold_timeout_ms = 1000.0;
  double reaction_latency_ms = 2.0;
  std::string serial = "SIM-0001";
  int robot_port = -1;  // -1: the robot bridge is off
  std::vector<double> probe_tcp_mm{0.0, 0.0, 200.0};
  std::vector<double> phantom_frame_mm{600.0, 0.0, 300.0};
  std::vector<double> phantom_frame_deg{0.0, 0.0, 180.0};
  double robot_cycle_ms = 1.0;
  std::vector<double> robot_start_mm;  // empty: the tip 50 mm above the phantom origin
  double robot_input_latency_ms = 1.0;
};

double pace_factor(const std::string& pace) {
  std::string error;
  const auto c = sim::parse_control("pace " + pace, error);
  if (!c) throw CLI::ValidationError("--pace", error);
  return std::get<sim::cmd::Pace>(*c).factor;
}

class Server {
 public:
  Server(const Options& o, sim::ByteServer device, sim::ByteServer control)
      : o_(o), device_(std::move(device)), control_(std::move(control)),
        pace_(pace_factor(o.pace)) {
    identity_.board = "palp-sim";
    identity_.serial = o_.serial.c_str();
    identity_.git_hash = PALP_GIT_HASH;
    identity_.capabilities = (1u << static_cast<unsigned>(proto::Capability::pressure)) |
                             (1u << static_cast<unsigned>(proto::Capability::contact_output)) |
                             (1u << static_cast<unsigned>(proto::Capability::simulated));
    sim::SimulationOptions so;
    so.hold_timeout_ms = o.hold_timeout_ms;
    so.reaction_latency_ms = o.reaction_latency_ms;
    sim_ = std::make_unique<sim::Simulation>(identity_, std::make_unique<sim::ModelPlant>(o.phantom, o.seed), so);
    if (o.robot_port >= 0) {
      sim::RobotWorldOptions w;
      for (int i = 0; i < 3; ++i) {
        w.probe_tcp_mm[i] = o.probe_tcp_mm[static_cast<std::size_t>(i)];
        w.phantom_frame_mm[i] = o.phantom_frame_mm[static_cast<std::size_t>(i)];
        w.phantom_frame_deg[i] = o.phantom_frame_deg[static_cast<std::size_t>(i)];
      }
      if (o.robot_start_mm.size() == 3) {
        w.start_at_tip_mm = true;
        for (std::size_t i = 0; i < 3; ++i) w.start_tip_mm[i] = o.robot_start_mm[i];
      }
      w.bridge.cycle_ms = o.robot_cycle_ms;
      w.bridge.seed = o.seed;
      w.input_latency_ms = o.robot_input_latency_ms;
      world_ = std::make_unique<sim::RobotWorld>(*sim_, w);
      robot_ = std::make_unique<sim::ModbusServer>(o.listen, static_cast<std::uint16_t>(o.robot_port));
      sim_->set_plant(make_plant(o.phantom, o.seed));
      place_on_arm();
    } else {
      mount(o.mount_mm[0], o.mount_mm[1], o.mount_mm[2]);
    }
  }

  int run() {
    t0_ = Clock::now();
    std::string robot;
    if (robot_) robot = ", robot bridge on " + robot_->address();
    std::printf("palp-sim listening on %s (device protocol), control on %s%s\n",
                device_.address().c_str(), control_.address().c_str(), robot.c_str());
    std::fflush(stdout);
    std::uint64_t virtual_at_sync = 0;
    Clock::time_point wall_at_sync = Clock::now();
    while (g_stop == 0) {
      // stall while the host has not drained: virtual time waits, nothing is dropped
      const bool had_robot_client = robot_client();
      if (robot_) {
        // the Modbus socket every 0.2 ms of wall time at most: its syscalls would otherwise
        // slow a fast-paced simulation by a third
        const std::uint64_t now_us = wall_us(t0_);
        world_->set_wall_us(now_us);
        if (now_us - last_robot_poll_us_ >= 200) {
          robot_->poll(*world_, now_us);
          last_robot_poll_us_ = now_us;
        }
      }
      const bool any_client = device_.has_client() || robot_client();
      const bool can_run =
          any_client && device_.tx_pending() + pending_.size() < kStallBytes;
      const auto ev = device_.poll(can_run && !sim_->holding() ? 0 : (robot_client() ? 1 : 2));
      if (ev.connected || (robot_client() && !had_robot_client && !device_.has_client())) {
        virtual_at_sync = sim_->ticks();
        wall_at_sync = Clock::now();
      }
      const std::vector<std::uint8_t> rx = device_.take_received();
      if (!rx.empty()) sim_->host_bytes(rx.data(), rx.size(), wall_us(t0_));
      serve_control();
      if (can_run) {
        std::uint32_t chunk = sim_->controller().control_rate_Hz() / 1000;  // 1 ms of virtual time
        if (pace_ > 0) {
          // run only as far as wall time allows at this pace
          const double wall_s = std::chrono::duration<double>(Clock::now() - wall_at_sync).count();
          const double allowed = wall_s * pace_ * sim_->controller().control_rate_Hz();
          const double done = static_cast<double>(sim_->ticks() - virtual_at_sync);
          if (done >= allowed) {
            chunk = 0;
            std::this_thread::sleep_for(std::chrono::microseconds(200));
          } else if (allowed - done < chunk) {
            chunk = static_cast<std::uint32_t>(allowed - done);
          }
        }
        if (chunk > 0) sim_->run(chunk, wall_us(t0_));
      } else if (!any_client) {
        // no host: virtual time stands still
        virtual_at_sync = sim_->ticks();
        wall_at_sync = Clock::now();
      }
      // device bytes keep their order: whatever the socket buffer refused goes first next time
      const std::vector<std::uint8_t> out = sim_->take_device_bytes();
      pending_.insert(pending_.end(), out.begin(), out.end());
      if (!device_.has_client()) pending_.clear();
      if (!pending_.empty() && device_.send(pending_.data(), pending_.size())) pending_.clear();
    }
    std::printf("palp-sim: stopped after %.3f s of virtual time\n", sim_->virtual_s());
    return 0;
  }

 private:
  static constexpr std::size_t kStallBytes = 64 * 1024;

  std::unique_ptr<sim::PlantLink> make_plant(const std::string& phantom, std::uint64_t seed) {
    auto model = std::make_unique<sim::ModelPlant>(phantom, seed);
    if (!world_) return model;
    return std::make_unique<sim::ArmMountedPlant>(std::move(model), *world_, *sim_);
  }

  plant::Plant& model() {
    if (world_) return static_cast<sim::ArmMountedPlant&>(sim_->plant()).inner().model();
    return static_cast<sim::ModelPlant&>(sim_->plant()).model();
  }

  bool robot_client() const { return robot_ && robot_->has_client(); }

  void mount(double x_mm, double y_mm, double z_mm) {
    mount_mm_ = {x_mm, y_mm, z_mm};
    model().set_mount(x_mm * 1e-3, y_mm * 1e-3, z_mm * 1e-3);
  }

  // with the robot on, the arm places the probe: the tip where the flange holds it now
  void place_on_arm() {
    double tip[3];
    world_->tip_in_phantom(tip);
    model().set_mount(tip[0], tip[1], tip[2]);
  }

  void reply(const std::string& line) {
    const std::string l = line + "\n";
    control_.send(reinterpret_cast<const std::uint8_t*>(l.data()), l.size());
  }

  void serve_control() {
    control_.poll(0);
    const std::vector<std::uint8_t> bytes = control_.take_received();
    control_line_.append(bytes.begin(), bytes.end());
    std::size_t eol;
    while ((eol = control_line_.find('\n')) != std::string::npos) {
      const std::string line = control_line_.substr(0, eol);
      control_line_.erase(0, eol + 1);
      std::string error;
      const auto c = sim::parse_control(line, error);
      if (!c) {
        reply("error: " + error);
        continue;
      }
      std::visit([&](const auto& cmd) { apply(cmd); }, *c);
    }
    if (control_line_.size() > 4096) {
      control_line_.clear();
      reply("error: line longer than 4096 bytes");
    }
  }

  void apply(const sim::cmd::Help&) { reply(std::string("ok ") + sim::control_help()); }
  void apply(const sim::cmd::Status&) {
    char buf[256];
    const auto& c = sim_->counters();
    std::snprintf(buf, sizeof buf,
                  "ok virtual_s=%.6f ticks=%llu pace=%g client=%d holding=%d phantom=%s "
                  "frames_out=%llu dropped=%llu corrupted=%llu holds=%llu",
                  sim_->virtual_s(), static_cast<unsigned long long>(sim_->ticks()), pace_,
                  device_.has_client() ? 1 : 0, sim_->holding() ? 1 : 0, phantom_.c_str(),
                  static_cast<unsigned long long>(c.frames_out),
                  static_cast<unsigned long long>(c.frames_dropped),
                  static_cast<unsigned long long>(c.frames_corrupted),
                  static_cast<unsigned long long>(c.holds));
    std::string line = buf;
    if (world_) {
      const auto& s = world_->bridge().status();
      const auto& rc = world_->bridge().counters();
      const auto& mc = robot_->counters();
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
                    robot_client() ? 1 : 0, proto::rb::enum_name(s.state), s.x_um * 1e-3,
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
                    static_cast<unsigned long long>(mc.refused), robot_->reply_delay_ms());
      line += r;
    }
    reply(line);
  }
  void apply(const sim::cmd::Mount& m) {
    if (world_) {
      reply("error: mount: the robot arm places the probe (palp-sim runs with --robot-port); "
            "move the arm instead");
      return;
    }
    mount(m.x_mm, m.y_mm, m.z_mm);
    reply("ok");
  }
  bool robot_on(const char* name) {
    if (robot_) return true;
    reply(std::string("error: ") + name + ": the robot bridge is off (start palp-sim with --robot-port)");
    return false;
  }
  void apply(const sim::cmd::RobotReplyDelay& d) {
    if (!robot_on("robot-reply-delay")) return;
    robot_->set_reply_delay_ms(d.ms);
    reply("ok");
  }
  void apply(const sim::cmd::RobotDrop&) {
    if (!robot_on("robot-drop")) return;
    const bool had = robot_->has_client();
    robot_->drop_client(*world_);
    reply(had ? "ok" : "ok no client");
  }
  void apply(const sim::cmd::RobotFreezeHeartbeat& f) {
    if (!robot_on("robot-freeze-heartbeat")) return;
    world_->bridge().freeze_heartbeat(f.on);
    reply("ok");
  }
  void apply(const sim::cmd::RobotReject& r) {
    if (!robot_on("robot-reject")) return;
    world_->bridge().reject_next(static_cast<proto::rb::Result>(r.result), r.count);
    reply("ok");
  }
  void apply(const sim::cmd::RobotFault&) {
    if (!robot_on("robot-fault")) return;
    world_->bridge().inject_fault();
    reply("ok");
  }
  void apply(const sim::cmd::Phantom& p) { rebuild_plant(p.name, seed_); }
  void apply(const sim::cmd::Seed& s) { rebuild_plant(phantom_, s.seed); }
  void apply(const sim::cmd::Pace& p) {
    pace_ = p.factor;
    reply("ok");
  }
  void apply(const sim::cmd::DropFrames& d) {
    sim_->options().drop_every = d.every;
    reply("ok");
  }
  void apply(const sim::cmd::CorruptFrames& d) {
    sim_->options().corrupt_every = d.every;
    reply("ok");
  }
  void apply(const sim::cmd::Announce& a) {
    fw::DeviceIdentity id = identity_;
    if (!a.actual) id.protocol = {a.major, a.minor, a.hash.value_or(proto::kSchemaHash)};
    sim_->controller().set_identity(id);
    reply("ok");
  }
  void apply(const sim::cmd::ReactionLatency& r) {
    sim_->options().reaction_latency_ms = r.ms;
    reply("ok");
  }
  void apply(const sim::cmd::HoldTimeout& h) {
    sim_->options().hold_timeout_ms = h.ms;
    reply("ok");
  }

  void rebuild_plant(const std::string& phantom, std::uint64_t seed) {
    try {
      sim_->set_plant(make_plant(phantom, seed));
      phantom_ = phantom;
      seed_ = seed;
      if (world_) place_on_arm();
      else mount(mount_mm_[0], mount_mm_[1], mount_mm_[2]);
      reply("ok");
    } catch (const std::exception& e) {
      reply(std::string("error: ") + e.what());
    }
  }

  Options o_;
  sim::ByteServer device_;
  sim::ByteServer control_;
  double pace_;
  fw::DeviceIdentity identity_;
  std::unique_ptr<sim::Simulation> sim_;
  std::unique_ptr<sim::RobotWorld> world_;     // with --robot-port
  std::unique_ptr<sim::ModbusServer> robot_;   // with --robot-port
  std::uint64_t last_robot_poll_us_ = 0;
  std::string phantom_ = o_.phantom;
  std::uint64_t seed_ = o_.seed;
  std::array<double, 3> mount_mm_{};
  std::string control_line_;
  std::vector<std::uint8_t> pending_;
  Clock::time_point t0_ = Clock::now();
};

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"palp-sim: the palp probe controller's firmware core against a physical model, in "
               "virtual time, served over a loopback socket (hil/README.md)"};
  app.add_option("--listen-address", o.listen, "IPv4 address to listen on (loopback by default)")
      ->capture_default_str();
  app.add_option("--port", o.port, "TCP port of the device protocol (0: pick a free one)")
      ->capture_default_str();
  app.add_option("--unix", o.unix_path, "serve the device protocol on this Unix socket instead");
  app.add_option("--control-port", o.control_port, "TCP port of the control channel (0: free)")
      ->capture_default_str();
  app.add_option("--phantom", o.phantom,
                 "specimen under the probe: none, hollow_1d, solid_1d, insert_1d, pad_2d")
      ->capture_default_str();
  app.add_option("--mount-mm", o.mount_mm,
                 "probe mount x y z in mm: the tip at the stroke origin, phantom frame")
      ->expected(3);
  app.add_option("--seed", o.seed, "noise seed (the same seed repeats a run)")->capture_default_str();
  app.add_option("--pace", o.pace, "realtime, fast, or a factor of real time")->capture_default_str();
  app.add_option("--hold-timeout-ms", o.hold_timeout_ms,
                 "wall time a contact event waits for the host's reaction")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--reaction-latency-ms", o.reaction_latency_ms,
                 "virtual time from an event to the host's reaction")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--serial", o.serial, "serial number the device reports")->capture_default_str();
  app.add_option("--robot-port", o.robot_port,
                 "serve the KUKA robot bridge (Modbus TCP) on this port (0: a free one); "
                 "without it the robot is off and --mount-mm places the probe")
      ->check(CLI::Range(0, 65535));
  app.add_option("--probe-tcp-mm", o.probe_tcp_mm,
                 "robot: the tip apex at stroke origin in the flange frame, x y z in mm")
      ->expected(3)
      ->capture_default_str();
  app.add_option("--phantom-frame-mm", o.phantom_frame_mm,
                 "robot: the phantom frame's origin in the robot base frame, x y z in mm")
      ->expected(3)
      ->capture_default_str();
  app.add_option("--phantom-frame-deg", o.phantom_frame_deg,
                 "robot: the phantom frame's orientation in the base frame, KUKA A B C in deg")
      ->expected(3)
      ->capture_default_str();
  app.add_option("--robot-start-mm", o.robot_start_mm,
                 "robot: start with the tip at this base-frame position, x y z in mm (default: "
                 "50 mm above the phantom origin), the probe along the phantom's +z")
      ->expected(3);
  app.add_option("--robot-cycle-ms", o.robot_cycle_ms, "robot: the bridge's cycle, virtual ms")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 20.0));
  app.add_option("--robot-input-latency-ms", o.robot_input_latency_ms,
                 "robot: contact-output line to digital input 1, virtual ms")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  CLI11_PARSE(app, argc, argv);

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGPIPE, SIG_IGN);
  try {
    if (o.listen != "127.0.0.1")
      std::fprintf(stderr, "palp-sim: warning: listening on %s, not only on loopback\n",
                   o.listen.c_str());
    pace_factor(o.pace);
    if (o.robot_port >= 0 && app.count("--mount-mm") > 0)
      std::fprintf(stderr, "palp-sim: warning: --mount-mm is ignored with --robot-port: the arm "
                           "places the probe (--robot-start-mm)\n");
    sim::ByteServer device = o.unix_path.empty() ? sim::ByteServer::tcp(o.listen, o.port)
                                                 : sim::ByteServer::unix_socket(o.unix_path);
    sim::ByteServer control = sim::ByteServer::tcp(o.listen, o.control_port);
    Server server(o, std::move(device), std::move(control));
    return server.run();
  } catch (const CLI::Error& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "palp-sim: %s\n", e.what());
    return 1;
  }
}
