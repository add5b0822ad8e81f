#pragma once
// Concrete is generated outside the bars (SPEC 8): no concrete centre closer to a bar's axis than
// D/2 + 0.5 r. During relaxation a bar pushes on the particles that overlap it, like a wall.
#include <algorithm>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/types.hpp"

namespace rcdem {

struct BarAxis {
  Vec3 a, b;    // ends of the axis
  Real radius;  // D / 2

  // The point of the axis segment closest to p.
  Vec3 closest(const Vec3& p) const {
    const Vec3 ab = b - a;
    const Real t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return a + t * ab;
  }
};

inline std::vector<BarAxis> bar_axes(const std::vector<BarSettings>& bars) {
  std::vector<BarAxis> axes;
  for (const auto& b : bars)
    for (const auto& [a, e] : b.chords()) axes.push_back({a, e, 0.5 * b.diameter});
  return axes;
}

// Push of the bars on a particle of radius r that overlaps them (a rigid cylinder of radius D/2).
inline Vec3 bar_push(const Vec3& p, Real r, const std::vector<BarAxis>& bars) {
  Vec3 push = Vec3::Zero();
  for (const auto& bar : bars) {
    const Vec3 d = p - bar.closest(p);
    const Real dist = d.norm();
    const Real overlap = bar.radius + r - dist;
    if (overlap > 0.0 && dist > 0.0) push += (overlap / dist) * d;
  }
  return push;
}

// Moves p radially out to `bar.radius + margin` from every bar axis it is closer to.
inline Vec3 keep_off_bars(Vec3 p, Real margin, const std::vector<BarAxis>& bars) {
  for (const auto& bar : bars) {
    const Vec3 c = bar.closest(p);
    const Vec3 d = p - c;
    const Real dist = d.norm();
    const Real min = bar.radius + margin;
    if (dist >= min) continue;
    // A centre exactly on the axis leaves sideways (any direction normal to the axis).
    Vec3 dir = dist > 0.0 ? Vec3(d / dist) : (bar.b - bar.a).unitOrthogonal();
    p = c + min * dir;
  }
  return p;
}

inline bool near_bar(const Vec3& p, Real margin, const std::vector<BarAxis>& bars) {
  for (const auto& bar : bars)
    if ((p - bar.closest(p)).norm() < bar.radius + margin) return true;
  return false;
}

}  // namespace rcdem
