#include "rcdem/config/specimen_geometry.hpp"

#include <algorithm>

namespace rcdem {

Real SpecimenGeometry::distance_to_boundary(const Vec3& p) const {
  Real d = std::min((p - lo).minCoeff(), (hi - p).minCoeff());
  if (notch.present()) {
    const Real half = 0.5 * notch.width;
    const Real top = lo.z() + notch.depth;
    const Real dx = std::abs(p.x() - notch.x_center) - half;  // > 0 outside the slot's x-band
    const Real dz = p.z() - top;                              // > 0 above the slot
    Real to_slot;
    if (dz <= 0.0)
      to_slot = dx;
    else if (dx <= 0.0)
      to_slot = dz;
    else
      to_slot = std::hypot(dx, dz);
    d = std::min(d, to_slot);
  }
  return d;
}

bool SpecimenGeometry::segment_crosses_notch(const Vec3& a, const Vec3& b) const {
  if (!notch.present()) return false;
  const Real sa = a.x() - notch.x_center;
  const Real sb = b.x() - notch.x_center;
  if ((sa < 0.0) == (sb < 0.0)) return false;
  // Height at which the centre-to-centre segment passes the slot's mid-plane.
  const Real t = sa / (sa - sb);
  const Real z = a.z() + t * (b.z() - a.z());
  return z < lo.z() + notch.depth;
}

}  // namespace rcdem
