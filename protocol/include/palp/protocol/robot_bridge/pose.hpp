// SPDX-License-Identifier: Apache-2.0
// KUKA's pose convention (protocol/robot-bridge.md §4), once, for the emulator and the SDK: a
// pose is a position and the ZYX Euler angles A, B, C, with the rotation R = Rz(A) Ry(B) Rx(C)
// (A about z, B about the new y, C about the newest x); the columns of R are the frame's x, y, z
// axes in the base frame. Plain arrays, no allocation, no library.
#pragma once

#include <cmath>

namespace palp::proto::rb {

/// A rotation matrix, row-major: m[row][column].
struct Rotation {
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
};

/// A rigid transform: p_base = R p_frame + t.
struct Transform {
  Rotation r;
  double t[3] = {0, 0, 0};
};

/// R = Rz(a) Ry(b) Rx(c), angles in rad.
inline Rotation rotation_from_abc(double a, double b, double c) {
  const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b),
               cc = std::cos(c), sc = std::sin(c);
  Rotation r;
  r.m[0][0] = ca * cb;
  r.m[0][1] = ca * sb * sc - sa * cc;
  r.m[0][2] = ca * sb * cc + sa * sc;
  r.m[1][0] = sa * cb;
  r.m[1][1] = sa * sb * sc + ca * cc;
  r.m[1][2] = sa * sb * cc - ca * sc;
  r.m[2][0] = -sb;
  r.m[2][1] = cb * sc;
  r.m[2][2] = cb * cc;
  return r;
}

/// The angles (rad) of a rotation, A and C in (-pi, pi], B in [-pi/2, pi/2]. At B = +-pi/2
/// (gimbal lock) C is 0 and A takes the whole turn.
inline void abc_from_rotation(const Rotation& r, double& a, double& b, double& c) {
  const double cb = std::hypot(r.m[0][0], r.m[1][0]);
  b = std::atan2(-r.m[2][0], cb);
  if (cb > 1e-12) {
    a = std::atan2(r.m[1][0], r.m[0][0]);
    c = std::atan2(r.m[2][1], r.m[2][2]);
  } else {
    a = std::atan2(-r.m[0][1], r.m[1][1]);
    c = 0.0;
  }
}

inline Rotation operator*(const Rotation& x, const Rotation& y) {
  Rotation r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r.m[i][j] = x.m[i][0] * y.m[0][j] + x.m[i][1] * y.m[1][j] + x.m[i][2] * y.m[2][j];
  return r;
}

inline Rotation transpose(const Rotation& x) {
  Rotation r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = x.m[j][i];
  return r;
}

/// R v.
inline void rotate(const Rotation& r, const double v[3], double out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = r.m[i][0] * v[0] + r.m[i][1] * v[1] + r.m[i][2] * v[2];
}

/// x ∘ y: first y, then x (p = x.r (y.r q + y.t) + x.t).
inline Transform operator*(const Transform& x, const Transform& y) {
  Transform out;
  out.r = x.r * y.r;
  rotate(x.r, y.t, out.t);
  for (int i = 0; i < 3; ++i) out.t[i] += x.t[i];
  return out;
}

inline Transform inverse(const Transform& x) {
  Transform out;
  out.r = transpose(x.r);
  rotate(out.r, x.t, out.t);
  for (int i = 0; i < 3; ++i) out.t[i] = -out.t[i];
  return out;
}

/// p_out = x p.
inline void apply(const Transform& x, const double p[3], double out[3]) {
  rotate(x.r, p, out);
  for (int i = 0; i < 3; ++i) out[i] += x.t[i];
}

}  // namespace palp::proto::rb
