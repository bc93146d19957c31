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

}  // namespace harbour::core
