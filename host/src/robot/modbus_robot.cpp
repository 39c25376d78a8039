// SPDX-License-Identifier: Apache-2.0
// ModbusRobot: the owner thread, the handshake rules of robot-bridge.md §8.1 and the link
// failure handling of §9.1/§9.2.
#include "robot/modbus_robot.hpp"

#include <cstdio>

#include "palp/error.hpp"
#include "probe/log.hpp"

namespace palp::detail {
namespace {

using namespace std::chrono_literals;

constexpr std::uint16_t kHostHeartbeat = rb::address_of<rb::HostControl>("host_heartbeat");
constexpr std::uint16_t kStopRequest = rb::address_of<rb::HostControl>("stop_request");
constexpr std::uint16_t kWatchdogMs = rb::address_of<rb::HostControl>("watchdog_ms");
constexpr auto kBridgeHeartbeatStale = 500ms;  // robot-bridge.md §9.2
constexpr std::size_t kRemembered = 64;        // commands whose ack and result are kept

double seconds(std::chrono::milliseconds t) { return static_cast<double>(t.count()) / 1000.0; }

std::string seconds_text(std::chrono::duration<double> t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g s", t.count());
  return buf;
}

bool ends_by_fault(rb::Result r) {
  return r == rb::Result::robot_fault || r == rb::Result::safety_stopped || r == rb::Result::watchdog;
}

/// The results after which latched_* belong to this motion (its guard or stop latched them).
bool latches(rb::Result r) {
  return r == rb::Result::guard_fired || r == rb::Result::stopped || r == rb::Result::watchdog;
}

RobotOptions checked(const RobotOptions& o) {
  if (o.watchdog.count() < rb::kMinWatchdogMs || o.watchdog.count() > rb::kMaxWatchdogMs)
    throw ConfigError("robot watchdog " + std::to_string(o.watchdog.count()) +
                      " ms is outside " + std::to_string(rb::kMinWatchdogMs) + ".." +
                      std::to_string(rb::kMaxWatchdogMs) + " ms (robot-bridge.md §5.3)");
  if (o.response_timeout.count() <= 0 || o.status_period.count() <= 0 || o.reconnect_for.count() < 0)
    throw ConfigError("robot options: response_timeout and status_period must be > 0 ms and "
                      "reconnect_for >= 0 ms");
  return o;
}

}  // namespace

ModbusRobot::ModbusRobot(const RobotUri& uri, const RobotOptions& options)
    : options_(checked(options)), link_(uri, options.response_timeout),
      heartbeat_period_(std::max(options.watchdog / 4, std::chrono::milliseconds(1))) {
  info_.uri = uri.canonical;
  try {
    link_.connect();
  } catch (const LinkDown& e) {
    throw RobotLinkError("cannot connect to the robot bridge at " + uri.canonical + ": " + e.what);
  }
  try {
    connect_checks(true);
  } catch (const LinkDown& e) {
    throw RobotLinkError("the robot bridge at " + uri.canonical +
                         " accepted the connection but did not answer the connect checks: " + e.what);
  }
  info_.map_major = id_.map_major;
  info_.map_minor = id_.map_minor;
  owner_ = std::thread([this] { owner_loop(); });
}

ModbusRobot::~ModbusRobot() {
  quitting_ = true;
  {
    std::lock_guard lock(mu_);
    quit_ = true;
  }
  cv_.notify_all();
  owner_.join();
}

// ---- the owner thread -------------------------------------------------------------------------

void ModbusRobot::owner_loop() {
  auto next_tick = Clock::now() + heartbeat_period_;
  std::unique_lock lock(mu_);
  while (!quit_) {
    cv_.wait_until(lock, next_tick, [&] { return quit_ || !tasks_.empty(); });
    if (quit_) break;
    if (Clock::now() >= next_tick) {
      lock.unlock();
      tick();
      lock.lock();
      next_tick += heartbeat_period_;
      if (next_tick < Clock::now()) next_tick = Clock::now() + heartbeat_period_;
    }
    while (!tasks_.empty() && !quit_) {
      auto task = std::move(tasks_.front());
      tasks_.pop_front();
      lock.unlock();
      task();
      lock.lock();
    }
  }
}

void ModbusRobot::tick() {
  try {
    if (!stalled_.empty()) {
      // Wait for the bridge's heartbeat to move again, then start over as after a connect (§9.2).
      rb::StatusBlock s;
      with_link([&] { s = read_status_raw(); });
      if (s.heartbeat != robot_heartbeat_) {
        reconnect("the bridge's heartbeat moved again");
        stalled_.clear();
      }
      return;
    }
    with_link([&] { link_.write_one(kHostHeartbeat, ++host_heartbeat_); });
    read_status();
  } catch (const Error&) {
    // A caller's next request reports the link; the heartbeat keeps trying.
  }
}

void ModbusRobot::connect_checks(bool first) {
  id_ = check_identification(link_.read(rb::Identification::kAddress, rb::Identification::kLength),
                             info_.uri);
  const rb::HostControl control =
      decode_control(link_.read(id_.control_address, rb::HostControl::kLength), info_.uri);
  const rb::StatusBlock status = read_status_raw();
  if (first) {
    next_stop_ = static_cast<std::uint16_t>(control.stop_request + 1);
    host_heartbeat_ = control.host_heartbeat;
  }
  // A new seq must differ from ack_seq (rule 3); a command being retried keeps its seq (rule 6).
  if (first || (!commit_pending_ && next_seq_ == status.ack_seq)) {
    next_seq_ = static_cast<std::uint16_t>(status.ack_seq + 1);
    if (next_seq_ == 0) next_seq_ = 1;
  }
  link_.write_one(kWatchdogMs, static_cast<std::uint16_t>(options_.watchdog.count()));
  link_.write_one(kHostHeartbeat, ++host_heartbeat_);
  have_robot_heartbeat_ = false;
  note(status);
}

void ModbusRobot::reconnect(const std::string& why) {
  const auto start = Clock::now();
  const auto deadline = start + options_.reconnect_for;
  std::string last = why;
  detail::log(LogLevel::warning, "robot bridge " + info_.uri + ": the link failed (" + why + "): reconnecting");
  for (;;) {
    try {
      link_.connect();
      connect_checks(false);
      detail::log(LogLevel::info, "robot bridge " + info_.uri + " reconnected after " + seconds_text(Clock::now() - start));
      return;
    } catch (const LinkDown& e) {
      last = e.what;
      link_.close();
    }
    const auto now = Clock::now();
    if (quitting_) throw RobotLinkError("robot bridge " + info_.uri + ": the Robot is being closed");
    if (now >= deadline)
      throw RobotLinkError("robot bridge " + info_.uri + " unreachable: the link failed (" + why +
                           ") and did not come back within " + seconds_text(now - start) +
                           "; last error: " + last);
    std::this_thread::sleep_for(std::min<Clock::duration>(50ms, deadline - now));
  }
}

template <class F>
void ModbusRobot::with_link(F&& f) {
  for (;;) {
    try {
      if (!link_.connected()) throw LinkDown{"not connected"};
      f();
      return;
    } catch (const LinkDown& e) {
      reconnect(e.what);
    }
  }
}

rb::StatusBlock ModbusRobot::read_status_raw() {
  const auto length = std::max<std::uint16_t>(id_.status_length, rb::StatusBlock::kLength);
  return decode_status(link_.read(id_.status_address, length), info_.uri);
}

rb::StatusBlock ModbusRobot::read_status() {
  throw_if_stalled();
  rb::StatusBlock s;
  with_link([&] { s = read_status_raw(); });
  note(s);
  return s;
}

void ModbusRobot::note(const rb::StatusBlock& s) {
  const auto now = Clock::now();
  if (!have_robot_heartbeat_ || s.heartbeat != robot_heartbeat_) {
    robot_heartbeat_ = s.heartbeat;
    robot_heartbeat_changed_ = now;
    have_robot_heartbeat_ = true;
  } else if (now - robot_heartbeat_changed_ >= kBridgeHeartbeatStale) {
    stalled_ = "robot bridge heartbeat stopped: " + info_.uri + " has answered with heartbeat " +
               std::to_string(s.heartbeat) + " for " + seconds_text(now - robot_heartbeat_changed_) +
               " (the bridge application is hung or stopped; no motion is commanded until it "
               "runs again)";
    throw RobotLinkError(stalled_);
  }
  if (s.ack_seq != 0 && codes_.count(s.ack_seq) && !acks_.count(s.ack_seq))
    acks_[s.ack_seq] = Ack{s.ack_result, s.reject_detail};
  if (s.done_seq != 0 && codes_.count(s.done_seq) && !finished_.count(s.done_seq)) {
    Finished f{s.result, s.guard_fired, std::nullopt};
    if ((s.status_bits & rb::bit(rb::StatusBit::latched_pose_valid)) && latches(s.result))
      f.latched = pose_from_registers(s.latched_x_um, s.latched_y_um, s.latched_z_um,
                                      s.latched_a_mdeg, s.latched_b_mdeg, s.latched_c_mdeg);
    finished_[s.done_seq] = f;
  }
}

void ModbusRobot::throw_if_stalled() const {
  if (!stalled_.empty()) throw RobotLinkError(stalled_);
}

void ModbusRobot::commit(const rb::Command& c) {
  bool retry = false;
  commit_pending_ = true;
  try {
    with_link([&] {
      if (retry && read_status_raw().ack_seq == c.seq) return;  // rule 6: it was taken
      retry = true;
      link_.write_block(c);
    });
  } catch (...) {
    commit_pending_ = false;
    throw;
  }
  commit_pending_ = false;
}

// ---- callers ----------------------------------------------------------------------------------

std::string ModbusRobot::name_of(std::uint16_t seq, rb::CommandCode code) const {
  return command_name(code) + " (seq " + std::to_string(seq) + ")";
}

ModbusRobot::Seen ModbusRobot::poll(std::uint16_t seq) {
  return call([&] {
    Seen seen;
    seen.status = read_status();
    if (auto a = acks_.find(seq); a != acks_.end()) seen.ack = a->second;
    if (auto f = finished_.find(seq); f != finished_.end()) seen.finished = f->second;
    if (auto c = codes_.find(seq); c != codes_.end()) seen.code = c->second;
    return seen;
  });
}

MotionHandle ModbusRobot::start(rb::Command c) {
  check_command_or_throw(c);
  const std::uint16_t seq = call([&] {
    throw_if_stalled();
    c.seq = next_seq_;
    next_seq_ = static_cast<std::uint16_t>(next_seq_ + 1);
    if (next_seq_ == 0) next_seq_ = 1;
    codes_[c.seq] = c.code;
    acks_.erase(c.seq);
    finished_.erase(c.seq);
    order_.push_back(c.seq);
    while (order_.size() > kRemembered) {
      codes_.erase(order_.front());
      acks_.erase(order_.front());
      finished_.erase(order_.front());
      order_.pop_front();
    }
    commit(c);
    return c.seq;
  });
  // Rule 4: the bridge acks within two cycles; allow for a reconnect on the way.
  const auto timeout = std::max<std::chrono::milliseconds>(2s, 4 * options_.response_timeout);
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    const Seen seen = poll(seq);
    if (seen.ack) {
      if (seen.ack->result == rb::Result::accepted) return MotionHandle{seq};
      const bool bad = seen.ack->result == rb::Result::rejected_bad_parameter;
      throw RobotRejectedError(rejection_text(c.code, seq, seen.ack->result, seen.ack->detail),
                               static_cast<std::uint16_t>(seen.ack->result),
                               bad ? seen.ack->detail : std::uint16_t{0xFFFF});
    }
    if (Clock::now() >= deadline)
      throw TimeoutError("the robot bridge " + info_.uri + " to acknowledge " + name_of(seq, c.code),
                         seconds(timeout), std::nullopt);
    std::this_thread::sleep_for(options_.status_period);
  }
}

RobotStatus ModbusRobot::status() {
  return status_from_block(call([&] { return read_status(); }));
}

MotionHandle ModbusRobot::start_move_lin(const Pose& target, double speed_m_per_s) {
  return start(motion_command(rb::CommandCode::move_lin, target, speed_m_per_s));
}

MotionHandle ModbusRobot::start_move_lin_rel(const Pose& offset, double speed_m_per_s) {
  return start(motion_command(rb::CommandCode::move_lin_rel, offset, speed_m_per_s));
}

MotionHandle ModbusRobot::start_move_ptp(const Pose& target, double speed_fraction) {
  return start(motion_command(rb::CommandCode::move_ptp, target, speed_fraction));
}

MotionHandle ModbusRobot::start_guarded_approach(const GuardedApproach& g) {
  return start(approach_command(g));
}

MotionResult ModbusRobot::wait(MotionHandle motion, std::chrono::milliseconds timeout) {
  const std::uint16_t seq = motion.seq;
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    const Seen seen = poll(seq);
    const rb::StatusBlock& s = seen.status;
    const auto now = Clock::now();
    if (seen.finished) {
      if (ends_by_fault(seen.finished->result))
        throw RobotFaultError(fault_text(seen.code, seq, seen.finished->result),
                              static_cast<std::uint16_t>(seen.finished->result));
      // Done may be set while the arm still brakes: its rest pose comes once it stands still
      // (or another command runs, or the time is up).
      const bool braking = s.state == rb::RobotState::moving && s.ack_seq == seq && s.done_seq == seq;
      if (!braking || now >= deadline) {
        MotionResult r;
        r.seq = seq;
        r.result = seen.finished->result;
        r.guard_fired = seen.finished->guard_fired;
        r.latched = seen.finished->latched;
        r.final_pose = pose_from_registers(s.x_um, s.y_um, s.z_um, s.a_mdeg, s.b_mdeg, s.c_mdeg);
        return r;
      }
    } else if (seen.code == rb::CommandCode::none) {
      throw ConfigError("robot wait: seq " + std::to_string(seq) +
                        " is not a motion this Robot started (or too old to remember)");
    } else if (s.done_seq != 0 && static_cast<std::uint16_t>(s.done_seq - seq) < 0x8000 &&
               s.done_seq != seq) {
      throw ProtocolError("robot bridge " + info_.uri + ": " + name_of(seq, seen.code) +
                          " finished unseen: done_seq is already " + std::to_string(s.done_seq));
    }
    if (now >= deadline)
      throw TimeoutError(name_of(seq, seen.code) + " to finish on the robot bridge " + info_.uri,
                         seconds(timeout), std::nullopt);
    std::this_thread::sleep_for(options_.status_period);
  }
}

RobotStatus ModbusRobot::stop(std::chrono::milliseconds timeout) {
  const std::uint16_t value = call([&] {
    throw_if_stalled();
    const std::uint16_t v = next_stop_;
    next_stop_ = static_cast<std::uint16_t>(next_stop_ + 1);
    with_link([&] { link_.write_one(kStopRequest, v); });
    return v;
  });
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    const rb::StatusBlock s = call([&] { return read_status(); });
    if (s.stop_seen == value) return status_from_block(s);
    if (Clock::now() >= deadline)
      throw TimeoutError("the robot bridge " + info_.uri + " to act on stop_request " +
                             std::to_string(value) + " (stop_seen is " + std::to_string(s.stop_seen) + ")",
                         seconds(timeout), std::nullopt);
    std::this_thread::sleep_for(options_.status_period);
  }
}

void ModbusRobot::hold(std::chrono::milliseconds timeout) {
  wait(start(plain_command(rb::CommandCode::hold)), timeout);
}

void ModbusRobot::set_tool(int id, const Pose& tcp_on_flange) {
  wait(start(tool_command(id, tcp_on_flange)), 2s);
}

void ModbusRobot::reset_fault() {
  wait(start(plain_command(rb::CommandCode::reset_fault)), 5s);
}

}  // namespace palp::detail

namespace palp {

std::unique_ptr<Robot> connect_robot(const std::string& uri, RobotOptions options) {
  return std::make_unique<detail::ModbusRobot>(detail::parse_robot_uri(uri), options);
}

}  // namespace palp
