// SPDX-License-Identifier: Apache-2.0
#include "palp/plant/robot_arm.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace palp::plant {

namespace {

using proto::rb::Rotation;

Rotation axis_angle(const double k[3], double angle) {
  const double c = std::cos(angle), s = std::sin(angle), v = 1.0 - c;
  Rotation r;
  r.m[0][0] = c + k[0] * k[0] * v;
  r.m[0][1] = k[0] * k[1] * v - k[2] * s;
  r.m[0][2] = k[0] * k[2] * v + k[1] * s;
  r.m[1][0] = k[1] * k[0] * v + k[2] * s;
  r.m[1][1] = c + k[1] * k[1] * v;
  r.m[1][2] = k[1] * k[2] * v - k[0] * s;
  r.m[2][0] = k[2] * k[0] * v - k[1] * s;
  r.m[2][1] = k[2] * k[1] * v + k[0] * s;
  r.m[2][2] = c + k[2] * k[2] * v;
  return r;
}

// The axis (unit) and angle in [0, pi] of a rotation.
void to_axis_angle(const Rotation& r, double k[3], double& angle) {
  const double tr = r.m[0][0] + r.m[1][1] + r.m[2][2];
  angle = std::acos(std::clamp((tr - 1.0) / 2.0, -1.0, 1.0));
  const double w[3] = {r.m[2][1] - r.m[1][2], r.m[0][2] - r.m[2][0], r.m[1][0] - r.m[0][1]};
  const double n = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  if (angle < 1e-12) {
    k[0] = 0, k[1] = 0, k[2] = 1;
    angle = 0;
  } else if (n > 1e-9) {
    for (int i = 0; i < 3; ++i) k[i] = w[i] / n;
  } else {  // angle ~ pi: R = 2 k k^T - I
    int i = 0;
    for (int j = 1; j < 3; ++j)
      if (r.m[j][j] > r.m[i][i]) i = j;
    const double ki = std::sqrt(std::max(0.0, (r.m[i][i] + 1.0) / 2.0));
    for (int j = 0; j < 3; ++j) k[j] = j == i ? ki : r.m[i][j] / (2.0 * ki);
  }
}

double norm3(const double v[3]) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

}  // namespace

Transform pose_from_xyzabc(double x_m, double y_m, double z_m, double a_rad, double b_rad,
                           double c_rad) {
  Transform t;
  t.r = proto::rb::rotation_from_abc(a_rad, b_rad, c_rad);
  t.t[0] = x_m, t.t[1] = y_m, t.t[2] = z_m;
  return t;
}

RobotArm::RobotArm(const Transform& flange, RobotArmConfig config)
    : config_(config), flange_(flange) {
  if (!(config_.accel_m_per_s2 > 0) || !(config_.brake_decel_m_per_s2 > 0) ||
      !(config_.stop_latency_s >= 0) || !(config_.workspace_radius_m > 0) ||
      !(config_.ptp_speed_m_per_s > 0))
    throw std::invalid_argument("robot arm: accelerations, workspace and PTP speed must be > 0, "
                                "the stop latency >= 0");
}

Transform RobotArm::tcp() const { return flange_ * tool_; }

bool RobotArm::set_tool(const Transform& tool) {
  if (moving_) return false;
  tool_ = tool;
  return true;
}

bool RobotArm::reachable(const Transform& tcp_target) const {
  const double* p = tcp_target.t;
  return p[2] >= 0.0 && norm3(p) <= config_.workspace_radius_m;
}

bool RobotArm::move_lin(const Transform& target, double speed) {
  if (moving_ || !(speed > 0) || !reachable(target)) return false;
  start_ = tcp();
  for (int i = 0; i < 3; ++i) dp_[i] = target.t[i] - start_.t[i];
  to_axis_angle(proto::rb::transpose(start_.r) * target.r, axis_, angle_);
  length_ = std::max(norm3(dp_), angle_ * kRotationLengthM);
  const double a = config_.accel_m_per_s2;
  vmax_ = std::min(speed, std::sqrt(length_ * a));  // the triangle's peak when short
  t_acc_ = vmax_ / a;
  t_total_ = length_ <= 0 ? 0.0 : length_ / vmax_ + t_acc_;
  t_ = 0, s_ = 0, v_ = 0;
  stop_requested_ = braking_ = false;
  reached_ = false;
  moving_ = true;
  if (length_ <= 0) {  // already there
    moving_ = false;
    reached_ = true;
  }
  return true;
}

bool RobotArm::move_lin_rel(const Transform& offset, double speed) {
  return move_lin(tcp() * offset, speed);
}

bool RobotArm::move_ptp(const Transform& target, int permille) {
  if (permille <= 0) return false;
  return move_lin(target, config_.ptp_speed_m_per_s * permille / 1000.0);
}

void RobotArm::stop() {
  if (!moving_ || stop_requested_) return;
  stop_requested_ = true;
  stop_at_t_ = t_ + config_.stop_latency_s;
}

double RobotArm::profile_s(double t) const {
  const double a = config_.accel_m_per_s2;
  if (t <= 0) return 0;
  if (t >= t_total_) return length_;
  if (t < t_acc_) return 0.5 * a * t * t;
  const double t_dec = t_total_ - t_acc_;
  if (t <= t_dec) return 0.5 * a * t_acc_ * t_acc_ + vmax_ * (t - t_acc_);
  const double r = t_total_ - t;
  return length_ - 0.5 * a * r * r;
}

double RobotArm::profile_v(double t) const {
  const double a = config_.accel_m_per_s2;
  if (t <= 0 || t >= t_total_) return 0;
  if (t < t_acc_) return a * t;
  if (t <= t_total_ - t_acc_) return vmax_;
  return a * (t_total_ - t);
}

void RobotArm::step(double dt) {
  if (!moving_ || !(dt > 0)) return;
  t_ += dt;
  if (stop_requested_ && !braking_ && t_ >= stop_at_t_ && stop_at_t_ < t_total_) {
    braking_ = true;
    brake_s0_ = profile_s(stop_at_t_);
    brake_v0_ = profile_v(stop_at_t_);
  }
  bool ended = false;
  if (braking_) {
    const double b = config_.brake_decel_m_per_s2;
    const double tau = t_ - stop_at_t_;
    const double t_stop = brake_v0_ / b;
    if (tau >= t_stop) {
      s_ = brake_s0_ + brake_v0_ * brake_v0_ / (2 * b);
      v_ = 0;
      ended = true;
    } else {
      s_ = brake_s0_ + brake_v0_ * tau - 0.5 * b * tau * tau;
      v_ = brake_v0_ - b * tau;
    }
  } else {
    s_ = profile_s(t_);
    v_ = profile_v(t_);
    if (t_ >= t_total_) ended = true;
  }
  if (s_ >= length_) {
    s_ = length_;
    ended = true;
  }
  place(s_);
  if (ended) {
    moving_ = false;
    v_ = 0;
    reached_ = s_ >= length_ - 1e-12;
    stop_requested_ = braking_ = false;
  }
}

void RobotArm::place(double s) {
  const double f = length_ > 0 ? s / length_ : 1.0;
  Transform tcp_now;
  tcp_now.r = start_.r * axis_angle(axis_, angle_ * f);
  for (int i = 0; i < 3; ++i) tcp_now.t[i] = start_.t[i] + dp_[i] * f;
  flange_ = tcp_now * proto::rb::inverse(tool_);
}

}  // namespace palp::plant
