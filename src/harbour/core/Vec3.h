#pragma once

#include <cmath>

namespace harbour::core {

/// Three-component vector of doubles; world frame is x east, y north, z up.
struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  constexpr Vec3& operator+=(const Vec3& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  constexpr Vec3& operator-=(const Vec3& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  constexpr Vec3& operator*=(double s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};

constexpr Vec3 operator+(Vec3 a, const Vec3& b) {
  return a += b;
}
constexpr Vec3 operator-(Vec3 a, const Vec3& b) {
  return a -= b;
}
constexpr Vec3 operator-(const Vec3& a) {
  return {-a.x, -a.y, -a.z};
}
constexpr Vec3 operator*(Vec3 a, double s) {
  return a *= s;
}
constexpr Vec3 operator*(double s, Vec3 a) {
  return a *= s;
}
constexpr double dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3& a) {
  return std::sqrt(dot(a, a));
}

/// Row-major 3x3 matrix; used for rotations (orthonormal) in this code base.
struct Mat3 {
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  static constexpr Mat3 identity() { return {}; }
  /// Rotation by `angle` [rad] about the unit axis `axis` (Rodrigues).
  static Mat3 rotation(const Vec3& axis, double angle);
  /// Rotation from roll (about x), pitch (about y), yaw (about z) [rad], applied as Rz·Ry·Rx.
  static Mat3 from_roll_pitch_yaw(double roll, double pitch, double yaw);

  constexpr Vec3 row(int i) const { return {m[i][0], m[i][1], m[i][2]}; }
  constexpr Vec3 column(int j) const { return {m[0][j], m[1][j], m[2][j]}; }
  constexpr Mat3 transposed() const {
    Mat3 t;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        t.m[i][j] = m[j][i];
    return t;
  }
};

constexpr Vec3 operator*(const Mat3& a, const Vec3& v) {
  return {dot(a.row(0), v), dot(a.row(1), v), dot(a.row(2), v)};
}
constexpr Mat3 operator*(const Mat3& a, const Mat3& b) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
  return r;
}

inline Mat3 Mat3::rotation(const Vec3& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  const double x = axis.x, y = axis.y, z = axis.z;
  Mat3 r;
  r.m[0][0] = t * x * x + c;
  r.m[0][1] = t * x * y - s * z;
  r.m[0][2] = t * x * z + s * y;
  r.m[1][0] = t * x * y + s * z;
  r.m[1][1] = t * y * y + c;
  r.m[1][2] = t * y * z - s * x;
  r.m[2][0] = t * x * z - s * y;
  r.m[2][1] = t * y * z + s * x;
  r.m[2][2] = t * z * z + c;
  return r;
}

inline Mat3 Mat3::from_roll_pitch_yaw(double roll, double pitch, double yaw) {
  return rotation({0, 0, 1}, yaw) * rotation({0, 1, 0}, pitch) * rotation({1, 0, 0}, roll);
}

/// Rigid transform: maps a point p in the local frame to rotation·p + position in the parent frame.
struct Pose {
  Mat3 rotation;
  Vec3 position;

  constexpr Vec3 to_parent(const Vec3& p) const { return rotation * p + position; }
  constexpr Vec3 to_local(const Vec3& p) const { return rotation.transposed() * (p - position); }
  constexpr Vec3 direction_to_parent(const Vec3& d) const { return rotation * d; }
  constexpr Vec3 direction_to_local(const Vec3& d) const { return rotation.transposed() * d; }
};

/// Unit quaternion x, y, z, w: a rotation where it must be interpolated or sent (a Mat3 everywhere else).
struct Quat {
  double x = 0.0, y = 0.0, z = 0.0, w = 1.0;

  /// From a rotation matrix (Shepperd: from its largest diagonal term).
  static Quat from(const Mat3& r) {
    const auto& m = r.m;
    const double trace = m[0][0] + m[1][1] + m[2][2];
    if (trace > 0.0) {
      const double s = 2.0 * std::sqrt(1.0 + trace);
      return {(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s};
    }
    if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
      const double s = 2.0 * std::sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]);
      return {0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s};
    }
    if (m[1][1] > m[2][2]) {
      const double s = 2.0 * std::sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]);
      return {(m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s};
    }
    const double s = 2.0 * std::sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]);
    return {(m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s};
  }
  /// Its rotation matrix (normalised first: a quaternion that travelled as floats).
  Mat3 matrix() const {
    const double n = std::sqrt(x * x + y * y + z * z + w * w);
    const double a = x / n, b = y / n, c = z / n, d = w / n;
    Mat3 r;
    r.m[0][0] = 1 - 2 * (b * b + c * c);
    r.m[0][1] = 2 * (a * b - c * d);
    r.m[0][2] = 2 * (a * c + b * d);
    r.m[1][0] = 2 * (a * b + c * d);
    r.m[1][1] = 1 - 2 * (a * a + c * c);
    r.m[1][2] = 2 * (b * c - a * d);
    r.m[2][0] = 2 * (a * c - b * d);
    r.m[2][1] = 2 * (b * c + a * d);
    r.m[2][2] = 1 - 2 * (a * a + b * b);
    return r;
  }
};

/// The angular velocity [rad/s, parent frame] that turns `from` into `to` in `dt_s` (the shorter way).
inline Vec3 angular_velocity(const Mat3& from, const Mat3& to, double dt_s) {
  const Quat q = Quat::from(to * from.transposed());
  const double sign = q.w < 0.0 ? -1.0 : 1.0;
  const Vec3 v{sign * q.x, sign * q.y, sign * q.z};
  const double s = length(v);
  if (s < 1e-12) return {};
  const double angle = 2.0 * std::atan2(s, sign * q.w);
  return (angle / (s * dt_s)) * v;
}

/// The rotation `r` turned on at angular velocity `omega` [rad/s, parent frame] for `t_s`.
inline Mat3 turned(const Mat3& r, const Vec3& omega, double t_s) {
  const double rate = length(omega);
  if (rate * t_s == 0.0) return r;
  return Mat3::rotation((1.0 / rate) * omega, rate * t_s) * r;
}

/// The rotation a fraction `f` (0-1) of the way from `a` to `b`: their quaternions interpolated and
/// normalised (nlerp; within 0.3 % of the angle of slerp's path for the few degrees a blend spans).
inline Mat3 between(const Mat3& a, const Mat3& b, double f) {
  const Quat p = Quat::from(a), q = Quat::from(b);
  const double sign = p.x * q.x + p.y * q.y + p.z * q.z + p.w * q.w < 0.0 ? -1.0 : 1.0;
  const double g = 1.0 - f, h = sign * f;
  return Quat{g * p.x + h * q.x, g * p.y + h * q.y, g * p.z + h * q.z, g * p.w + h * q.w}.matrix();
}

}  // namespace harbour::core
