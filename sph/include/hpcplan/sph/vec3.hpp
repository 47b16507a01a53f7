#pragma once
// The little 3D vector algebra the fluid needs (the fluid is always 3D; z is up).
#include <array>
#include <cmath>

namespace hpcplan::sph {

using Vec3 = std::array<double, 3>;

inline Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3 operator*(double s, const Vec3& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}

// An axis-aligned box [lo, hi], closed.
struct Box3 {
  Vec3 lo{}, hi{};
  Vec3 size() const { return hi - lo; }
  bool contains(const Vec3& p) const {
    for (int k = 0; k < 3; ++k)
      if (!(p[k] >= lo[k] && p[k] <= hi[k])) return false;
    return true;
  }
  // Strictly inside: a point on a face is not in the interior.
  bool interior_contains(const Vec3& p) const {
    for (int k = 0; k < 3; ++k)
      if (!(p[k] > lo[k] && p[k] < hi[k])) return false;
    return true;
  }
};

}  // namespace hpcplan::sph
