#pragma once
// The closest points of two segments (Ericson, Real-Time Collision Detection, 5.1.9): the bars'
// layout check (how close two bars come) and the ties where two bars touch use the same geometry.
#include <algorithm>

#include "rcdem/core/types.hpp"

namespace rcdem {

struct SegmentClosestPoints {
  Real s, t;     // parameters in [0, 1] along p0-p1 and q0-q1
  Real distance;  // |p(s) - q(t)|
};

// Closest points of segments p0-p1 and q0-q1, clamped to both; for parallel segments, the one with
// s = 0 where it is among them.
inline SegmentClosestPoints closest_points(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                           const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const Real a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r), c = d1.dot(r);
  const Real b = d1.dot(d2), denom = a * e - b * b;
  Real s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  Real t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return {s, t, (p0 + s * d1 - (q0 + t * d2)).norm()};
}

}  // namespace rcdem
