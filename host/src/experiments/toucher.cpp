// SPDX-License-Identifier: Apache-2.0
// The guarded-approach touch (trace.hpp): search, back off, settle, slow approach, read at rest.
#include "toucher.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <thread>

#include "experiment_common.hpp"
#include "palp/analysis/indentation.hpp"

namespace palp::detail {

namespace rb = proto::rb;
using namespace std::chrono_literals;

namespace {
using experiment::kCountM;
constexpr double kSettleS = 1.2;        // the floating coil's ring-down (zeta 0.26, 16.5 rad/s)
constexpr double kRestS = 0.05;         // the contact settles after the arm stops
constexpr double kSearchSpeed = 10e-3;  // the coarse search, m/s
constexpr double kBackOff = 0.5e-3;     // from the first touch before the slow approach
constexpr double kMeasurableM = 4e-6;   // overtravel that tells a contact stiffness
constexpr double kStaleInputS = 1.0;    // longest the robot's input may lag the contact line
constexpr double kTurnedRad = 0.1 * std::numbers::pi / 180;  // a turn that re-floats the coil
constexpr double kCurrentStepA = 1e-3;  // a smaller tilt compensation is left out
constexpr int kCompensationPasses = 4;  // 25 degrees in palp-sim: 33, 17, 1 mA

std::array<double, 3> tool_z(const Pose& p) {
  const rb::Rotation r = rb::rotation_from_abc(p.a_rad, p.b_rad, p.c_rad);
  return {r.m[0][2], r.m[1][2], r.m[2][2]};
}

double angle(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::acos(std::clamp(a[0] * b[0] + a[1] * b[1] + a[2] * b[2], -1.0, 1.0));
}

std::string mm(double m) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f mm", m * 1e3);
  return b;
}
}  // namespace

rb::Transform transform_of(const Pose& p) {
  rb::Transform t;
  t.r = rb::rotation_from_abc(p.a_rad, p.b_rad, p.c_rad);
  t.t[0] = p.x_m, t.t[1] = p.y_m, t.t[2] = p.z_m;
  return t;
}

Pose pose_of(const rb::Transform& t) {
  Pose p;
  p.x_m = t.t[0], p.y_m = t.t[1], p.z_m = t.t[2];
  rb::abc_from_rotation(t.r, p.a_rad, p.b_rad, p.c_rad);
  return p;
}

Pose orientation_along(const double n[3], double a, double b_near, double c_near) {
  // v = Rz(-A) n = (sin B cos C, -sin C, cos B cos C)
  const double v[3] = {std::cos(a) * n[0] + std::sin(a) * n[1],
                       -std::sin(a) * n[0] + std::cos(a) * n[1], n[2]};
  const double cos_c = std::sqrt(std::max(0.0, 1.0 - v[1] * v[1]));
  if (cos_c < 1e-6)
    throw ConfigError("a tool axis perpendicular to the base's z turned by A has no B (cos C = 0): "
                      "tilt the work object or the surface less");
  auto wrapped = [](double d) { return std::remainder(d, 2 * std::numbers::pi); };
  Pose best;
  double best_d = INFINITY;
  for (double sign : {1.0, -1.0}) {
    const double b = std::atan2(sign * v[0], sign * v[2]);
    const double c = std::atan2(-v[1], sign * cos_c);
    const double d = std::hypot(wrapped(b - b_near), wrapped(c - c_near));
    if (d < best_d) best_d = d, best.b_rad = b, best.c_rad = c;
  }
  best.a_rad = a;
  return best;
}

struct Toucher::Approach {
  MotionResult motion;
  std::optional<ContactEvent> event;
};

Toucher::Toucher(Probe& probe, Robot& robot, const Rig& rig, std::function<bool()> cancelled)
    : probe_(probe), robot_(robot), rig_(rig), cancelled_(std::move(cancelled)) {}

void Toucher::check_cancelled() const {
  if (cancelled_ && cancelled_()) throw Cancelled{};
}

void Toucher::wait_device(double dt_s) {
  const double until = probe_.status().t_device_s + dt_s;
  while (probe_.status().t_device_s < until) {
    check_cancelled();
    std::this_thread::sleep_for(1ms);
  }
}

double Toucher::stroke_now_m() { return probe_.status().encoder_counts * kCountM; }

void Toucher::prepare() {
  if (floating_) return;
  robot_.set_tool(rig_.tool_id, rig_.tool_tcp);
  Params p = probe_.params();
  p.contact_output = proto::ContactOutputMode::active_high;
  probe_.set_params(p);
  experiment::float_coil(probe_, rig_.watch_current_A + offset_A_,
                         "is watch_current_A above the float current?");
  wait_device(kSettleS);
  floating_stroke_m_ = stroke_now_m();
  floating_axis_ = tool_z(robot_.pose());
  floating_ = true;
  if (!upright_stroke_m_ && offset_A_ == 0.0 &&
      angle(floating_axis_, tool_z(pose_of(wo_))) <= kTurnedRad)
    upright_stroke_m_ = floating_stroke_m_;
}

void Toucher::arm() {
  ContactWatchProgram w;
  w.hold_current_A = static_cast<float>(rig_.watch_current_A + offset_A_);
  w.threshold_counts = static_cast<std::uint32_t>(std::lround(rig_.contact_threshold_m / kCountM));
  w.timeout_s = 0.0f;
  probe_.load(w);
  probe_.start();
}

Toucher::Approach Toucher::approach(double speed, double travel_m) {
  arm();
  GuardedApproach g;
  g.axis = rb::Axis::tool_z;
  g.speed_m_per_s = speed;
  g.max_travel_m = travel_m;
  g.guard_host_stop = true;
  g.digital_input = rig_.contact_input;
  Approach a;
  const auto deadline = std::chrono::steady_clock::now() + 10s +
                        std::chrono::milliseconds(static_cast<long>(4000 * travel_m / speed));
  std::optional<double> stale_since_s;
  for (;;) {
    const MotionHandle h = robot_.start_guarded_approach(g);
    for (;;) {
      check_cancelled();
      a.event = probe_.wait_contact(2ms);
      if (a.event) {
        robot_.stop();  // the host's path; the robot's own input may already have stopped it
        break;
      }
      if (robot_.status().done_seq == h.seq) break;
      if (std::chrono::steady_clock::now() > deadline)
        throw TimeoutError("the guarded approach to end", 4 * travel_m / speed + 10, std::nullopt);
    }
    a.motion = robot_.wait(h, 5s);
    if (a.event) break;
    if (!stopped_by_the_input(a.motion)) {
      a.event = probe_.wait_contact(a.motion.result == rb::Result::guard_fired ? 500ms : 0ms);
      break;
    }
    // The robot's input stopped it but the watch has seen no contact: the robot still sees the
    // previous contact's line, which the watch's ProgramStart lowered less than the robot's input
    // latency ago. Approach again once that level is gone (bounded: a stuck input is an error).
    const Status st = probe_.status();
    if (st.program_state != proto::ProgramState::running) {
      a.event = probe_.wait_contact(500ms);  // the watch fired: the robot's input was first
      break;
    }
    if (!stale_since_s) stale_since_s = st.t_device_s;
    if (st.t_device_s - *stale_since_s > kStaleInputS)
      throw Error("the robot's digital input " + std::to_string(rig_.contact_input) +
                  " stays high while the probe's contact line is low (for " +
                  std::to_string(std::lround(kStaleInputS * 1e3)) + " ms of device time): check the wiring of the contact line");
  }
  return a;
}

bool Toucher::stopped_by_the_input(const MotionResult& m) const {
  return m.result == rb::Result::guard_fired &&
         (m.guard_fired & rb::bit(rb::GuardSource::digital_input)) != 0;
}

void Toucher::back_off(double distance_m) {
  robot_.move_lin_rel(Pose{0, 0, -distance_m, 0, 0, 0}, rig_.travel_speed_m_per_s);
}

void Toucher::release_coil() {
  probe_.stop();
  floating_ = false;
}

void Toucher::set_work_object(const Pose& work_object) {
  wo_ = transform_of(work_object);
  wo_inv_ = rb::inverse(wo_);
}

Pose Toucher::tcp_at(double x, double y, double z) const {
  rb::Transform t;
  t.r = wo_.r;
  const double p[3] = {x, y, z};
  rb::apply(wo_, p, t.t);
  return pose_of(t);
}

Pose Toucher::tcp_along(const double point[3], const double normal[3], double distance) const {
  const double wo_p[3] = {point[0] - distance * normal[0], point[1] - distance * normal[1],
                          point[2] - distance * normal[2]};
  double n[3];
  rb::rotate(wo_.r, normal, n);
  const Pose wo = pose_of(wo_);
  Pose p = orientation_along(n, wo.a_rad, wo.b_rad, wo.c_rad);
  double t[3];
  rb::apply(wo_, wo_p, t);
  p.x_m = t[0], p.y_m = t[1], p.z_m = t[2];
  return p;
}

void Toucher::turn_upright() {
  robot_.set_tool(rig_.tool_id, rig_.tool_tcp);  // the pose is the probe's TCP's
  Pose p = robot_.pose();
  const Pose wo = pose_of(wo_);
  p.a_rad = wo.a_rad, p.b_rad = wo.b_rad, p.c_rad = wo.c_rad;
  robot_.move_lin(p, rig_.travel_speed_m_per_s);
}

void Toucher::rise_to(double clearance) {
  const Pose now = robot_.pose();
  const double b[3] = {now.x_m, now.y_m, now.z_m};
  double w[3];
  rb::apply(wo_inv_, b, w);
  if (w[2] > -clearance) {
    Pose up = tcp_at(w[0], w[1], -clearance);
    up.a_rad = now.a_rad, up.b_rad = now.b_rad, up.c_rad = now.c_rad;
    robot_.move_lin(up, rig_.travel_speed_m_per_s);
  }
}

void Toucher::make_safe_and_raise() {
  make_safe();
  try {
    rise_to(rig_.safe_height_m + kFullStrokeM);
  } catch (const std::exception&) {
  }
}

void Toucher::make_safe() {
  try { robot_.stop(); } catch (const std::exception&) {}
  try { release_coil(); } catch (const std::exception&) {}
}

Touch Toucher::touch(const Pose& start, double search_travel, std::optional<double> approach_speed) {
  Touch t;
  prepare();
  robot_.move_lin(start, rig_.travel_speed_m_per_s);
  // a tool turned since the coil was floated floats elsewhere (its weight along the axis is
  // another): take the floating position again where this approach starts
  const std::array<double, 3> axis = tool_z(start);
  if (angle(axis, floating_axis_) > kTurnedRad) {
    wait_device(kSettleS);
    floating_stroke_m_ = stroke_now_m();
    floating_axis_ = axis;
    // float where the upright coil floats: the current makes up the weight along the axis that
    // the turn took away or added, k_v (s_upright - s) / K_f; K_f(s) is not flat behind the
    // float (a coil floated back is pushed harder than that says), so again until it is there
    for (int pass = 0; compensate_tilt_ && upright_stroke_m_ && pass < kCompensationPasses;
         ++pass) {
      const analysis::IndentationParams k;
      const double more = k.spring_N_per_m * (*upright_stroke_m_ - floating_stroke_m_) /
                          k.force_constant_N_per_A;
      if (std::abs(more) <= kCurrentStepA) break;
      offset_A_ += more;
      release_coil();
      wait_device(kSettleS);  // the coil back on its rear stop
      prepare();
    }
  }
  const double pushed = floating_stroke_m_ - stroke_now_m();
  if (std::abs(pushed) >= rig_.contact_threshold_m)
    throw ConfigError("the tip already touches something at the start of the approach (the coil is " +
                      mm(pushed) + " off its floating position): raise safe_height_mm above the specimen");
  const double search = std::max(rig_.approach_speed_m_per_s, std::min(kSearchSpeed, rig_.travel_speed_m_per_s));
  Approach coarse = approach(search, search_travel);
  if (!coarse.event) {
    release_coil();  // the search's watch still runs: the next touch's watch would be refused busy
    t.reason = "no contact within " + mm(search_travel) + " of travel";
    return t;
  }
  // back off until the tip is kBackOff clear of the surface: by kBackOff plus how far the coil is
  // pushed in now (the search's overtravel past the contact, which grows with the stop latency:
  // 0.5 mm at 10 mm/s and 50 ms, and then a fixed 0.5 mm would start the slow approach in contact)
  const double back_off = kBackOff + std::max(0.0, floating_stroke_m_ - stroke_now_m());
  robot_.move_lin_rel(Pose{0, 0, -back_off, 0, 0, 0}, search);
  wait_device(kSettleS);
  const double stroke_free = stroke_now_m();
  Approach fine = approach(approach_speed.value_or(rig_.approach_speed_m_per_s), back_off + kBackOff);
  if (!fine.event) {
    release_coil();
    t.reason = "no contact within " + mm(back_off + kBackOff) + " of the first touch";
    return t;
  }
  wait_device(kRestS);
  TracePoint& m = t.at_rest;
  const RobotStatus rest = robot_.status();
  m.tcp_at_rest = rest.pose;
  m.stroke_at_rest_m = stroke_now_m();
  m.guard_fired = fine.motion.guard_fired;
  const double kv = analysis::IndentationParams{}.spring_N_per_m;
  const double F = kv * std::max(0.0, stroke_free - m.stroke_at_rest_m);
  m.detection_force_N = F;
  const rb::Transform tcp = transform_of(rest.pose);
  if (fine.motion.latched) {
    const Pose& l = *fine.motion.latched;
    const double d[3] = {rest.pose.x_m - l.x_m, rest.pose.y_m - l.y_m, rest.pose.z_m - l.z_m};
    m.overtravel_m = d[0] * tcp.r.m[0][2] + d[1] * tcp.r.m[1][2] + d[2] * tcp.r.m[2][2];
  }
  // the contact stiffness from the approach itself: from the event (push-back = the threshold)
  // to rest the arm moved `overtravel` and the coil gave way by c; the rest, d, went into the
  // specimen while the force rose from F1 to F. Hertz, delta = a F^(2/3), gives a from that pair
  // and k_c = dF/d(delta) = 1.5 F / delta at F. Too little overtravel to tell: none.
  const double c = fine.event->encoder_counts * kCountM - m.stroke_at_rest_m;
  const double d = m.overtravel_m - c;
  const double F1 = kv * std::max(0.0, stroke_free - fine.event->encoder_counts * kCountM);
  const double span = std::pow(F, 2.0 / 3.0) - std::pow(F1, 2.0 / 3.0);
  if (F > 0 && d >= kMeasurableM && span > 0) {
    const double delta = d / span * std::pow(F, 2.0 / 3.0);
    m.contact_stiffness_N_per_m = 1.5 * F / delta;
  }
  m.ok = t.ok = true;
  return t;
}

}  // namespace palp::detail
