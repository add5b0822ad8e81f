#pragma once
// The region a specimen's concrete fills: an axis-aligned box, optionally with a central notch
// (a slot cut up from the bottom face across the full width).
#include "rcdem/core/types.hpp"

namespace rcdem {

struct Notch {
  Real x_center = 0.0;  // slot mid-plane
  Real width = 0.0;
  Real depth = 0.0;  // from the bottom face z = lo.z
  bool present() const { return depth > 0.0; }
};

struct SpecimenGeometry {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
  Notch notch;

  Vec3 size() const { return hi - lo; }
  Real box_volume() const { return size().prod(); }
  Real volume() const {
    return box_volume() - (notch.present() ? notch.width * notch.depth * size().y() : 0.0);
  }
  bool in_notch(const Vec3& p) const {
    return notch.present() && std::abs(p.x() - notch.x_center) < 0.5 * notch.width &&
           p.z() < lo.z() + notch.depth;
  }
  // Distance from an inside point to the nearest face, notch faces included.
  Real distance_to_boundary(const Vec3& p) const;
  // Whether the segment a-b crosses the notch (then the two particles share no contact).
  bool segment_crosses_notch(const Vec3& a, const Vec3& b) const;
};

}  // namespace rcdem
