// SPDX-License-Identifier: Apache-2.0
// palp::Robot over Modbus TCP (protocol/robot-bridge.md): one owner thread holds the libmodbus
// context; callers post tasks to it and wait for their results. The owner also keeps the host
// heartbeat (every watchdog/4) and reads the status block with it, so a bridge whose heartbeat
// stops is noticed even while no caller waits.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <type_traits>

#include "palp/robot.hpp"
#include "robot/modbus_link.hpp"
#include "robot/robot_convert.hpp"
#include "robot/robot_uri.hpp"

namespace palp::detail {

class ModbusRobot final : public Robot {
 public:
  /// Connects and runs the connect checks (§8.1 rule 1) on the calling thread, then starts the
  /// owner. Throws RobotLinkError, VersionError, ProtocolError.
  ModbusRobot(const RobotUri& uri, const RobotOptions& options);
  ~ModbusRobot() override;

  const RobotInfo& info() const override { return info_; }
  RobotStatus status() override;
  MotionHandle start_move_lin(const Pose& target, double speed_m_per_s) override;
  MotionHandle start_move_lin_rel(const Pose& offset, double speed_m_per_s) override;
  MotionHandle start_move_ptp(const Pose& target, double speed_fraction) override;
  MotionHandle start_guarded_approach(const GuardedApproach& g) override;
  MotionResult wait(MotionHandle motion, std::chrono::milliseconds timeout) override;
  RobotStatus stop(std::chrono::milliseconds timeout) override;
  void hold(std::chrono::milliseconds timeout) override;
  void set_tool(int id, const Pose& tcp_on_flange) override;
  void reset_fault() override;

 private:
  using Clock = std::chrono::steady_clock;
  struct Ack {
    rb::Result result = rb::Result::none;
    std::uint16_t detail = 0;
  };
  struct Finished {
    rb::Result result = rb::Result::none;
    std::uint16_t guard_fired = 0;
    std::optional<Pose> latched;
  };
  struct Seen {  // what a caller's poll learns, copied out of the owner
    rb::StatusBlock status;
    std::optional<Ack> ack;
    std::optional<Finished> finished;
    rb::CommandCode code = rb::CommandCode::none;
  };

  // --- any thread ---------------------------------------------------------------------------
  /// Runs f on the owner thread and returns its result (or rethrows its exception).
  template <class F>
  std::invoke_result_t<F&> call(F&& f);
  /// Checks c locally (ConfigError), commits it with a new seq and waits for its ack.
  MotionHandle start(rb::Command c);
  Seen poll(std::uint16_t seq);
  std::string name_of(std::uint16_t seq, rb::CommandCode code) const;

  // --- the owner thread only ----------------------------------------------------------------
  void owner_loop();
  void tick();
  /// §8.1 rule 1 (and the watchdog and a heartbeat); first: take seq and stop values from it.
  void connect_checks(bool first);
  /// Closes, reconnects and redoes the connect checks until options.reconnect_for has passed;
  /// then RobotLinkError naming the URI and the last error.
  void reconnect(const std::string& why);
  /// Runs f; on a broken link reconnects and runs it again.
  template <class F>
  void with_link(F&& f);
  rb::StatusBlock read_status_raw();
  /// A status read with the bridge-heartbeat check and the ack/done bookkeeping.
  rb::StatusBlock read_status();
  void note(const rb::StatusBlock& s);
  void throw_if_stalled() const;
  /// §8.1 rule 3, and rule 6 when the write has to be retried.
  void commit(const rb::Command& c);

  const RobotOptions options_;
  RobotInfo info_;
  ModbusLink link_;
  const std::chrono::milliseconds heartbeat_period_;

  // owner state
  rb::Identification id_{};
  std::uint16_t next_seq_ = 1, next_stop_ = 1, host_heartbeat_ = 0;
  bool commit_pending_ = false;
  std::uint16_t robot_heartbeat_ = 0;
  bool have_robot_heartbeat_ = false;
  Clock::time_point robot_heartbeat_changed_{};
  std::string stalled_;  // non-empty: the bridge's heartbeat stopped (the RobotLinkError text)
  std::map<std::uint16_t, Ack> acks_;
  std::map<std::uint16_t, Finished> finished_;
  std::map<std::uint16_t, rb::CommandCode> codes_;
  std::deque<std::uint16_t> order_;  // seqs in commit order, to forget the oldest

  // shared with callers
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::function<void()>> tasks_;
  bool quit_ = false;
  std::atomic<bool> quitting_{false};  // read by a reconnect in progress, so closing never waits
  std::thread owner_;
};

template <class F>
std::invoke_result_t<F&> ModbusRobot::call(F&& f) {
  using R = std::invoke_result_t<F&>;
  auto task = std::make_shared<std::packaged_task<R()>>(std::forward<F>(f));
  std::future<R> result = task->get_future();
  {
    std::lock_guard lock(mu_);
    tasks_.push_back([task] { (*task)(); });
  }
  cv_.notify_all();
  return result.get();
}

}  // namespace palp::detail
