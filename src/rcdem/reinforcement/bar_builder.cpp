#include "rcdem/reinforcement/bar_builder.hpp"

#include <algorithm>
#include <cmath>

#include "rcdem/core/error.hpp"

namespace rcdem {

namespace {
void check_bar(Real length, Real diameter, const SteelMaterial& steel,
               Real target_cylinder_length) {
  if (!(diameter > 0.0) || !std::isfinite(diameter))
    fail("bar: the diameter must be positive (got {} m)", diameter);
  if (!std::isfinite(length) || length < diameter)
    fail("bar: its length ({} m) must be at least its diameter ({} m)", length, diameter);
  if (!(target_cylinder_length > 0.0) || !std::isfinite(target_cylinder_length))
    fail("bar: the cylinder length must be positive (got {} m)", target_cylinder_length);
  if (!(steel.young_modulus > 0.0) || !(steel.poisson_ratio > -1.0 && steel.poisson_ratio < 0.5) ||
      !(steel.yield_strength > 0.0) || !(steel.density > 0.0))
    fail("bar: steel needs E > 0, -1 < nu < 0.5, f_y > 0 and density > 0 (got {}, {}, {}, {})",
         steel.young_modulus, steel.poisson_ratio, steel.yield_strength, steel.density);
}
}  // namespace

Bar build_straight_bar(const Vec3& start, const Vec3& end, Real diameter,
                       const SteelMaterial& steel, Real target_cylinder_length) {
  const Real length = (end - start).norm();
  check_bar(length, diameter, steel, target_cylinder_length);
  const auto n = static_cast<Index>(std::max(1.0, std::round(length / target_cylinder_length)));
  const Vec3 axis = (end - start) / length;
  const Real piece = length / static_cast<Real>(n);
  Bar bar{diameter, steel, {}, {}};
  bar.cylinders.reserve(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i)
    bar.cylinders.push_back({start + (static_cast<Real>(i) + 0.5) * piece * axis, axis, piece});
  for (Index i = 0; i + 1 < n; ++i) bar.nodes.push_back({i, i + 1});
  return bar;
}

Bar build_polyline_bar(const std::vector<Vec3>& points, bool closed, Real diameter,
                       const SteelMaterial& steel, Real target_cylinder_length) {
  Real length = 0.0;
  const std::size_t chords = closed ? points.size() : points.size() - 1;
  for (std::size_t j = 0; j < chords; ++j)
    length += (points[(j + 1) % points.size()] - points[j]).norm();
  check_bar(length, diameter, steel, target_cylinder_length);
  Bar bar{diameter, steel, {}, {}};
  for (std::size_t j = 0; j < chords; ++j) {
    const Vec3 a = points[j], b = points[(j + 1) % points.size()];
    const Real l = (b - a).norm();
    const auto n = static_cast<Index>(std::max(1.0, std::round(l / target_cylinder_length)));
    const Vec3 axis = (b - a) / l;
    const Real piece = l / static_cast<Real>(n);
    for (Index i = 0; i < n; ++i)
      bar.cylinders.push_back({a + (static_cast<Real>(i) + 0.5) * piece * axis, axis, piece});
  }
  const auto count = static_cast<Index>(bar.cylinders.size());
  for (Index i = 0; i + 1 < count; ++i) bar.nodes.push_back({i, i + 1});
  if (closed && count > 2) bar.nodes.push_back({count - 1, 0});
  return bar;
}

std::vector<InteractionNode> make_bar_nodes(const Bar& bar,
                                            const std::vector<Quat>& reference_orientation) {
  if (reference_orientation.size() != bar.cylinders.size())
    fail("bar: {} orientations given for {} cylinders", reference_orientation.size(),
         bar.cylinders.size());
  std::vector<InteractionNode> nodes;
  nodes.reserve(bar.nodes.size());
  for (const auto& [a, b] : bar.nodes) {
    const auto ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
    nodes.push_back(make_interaction_node(bar.cylinders[ia], reference_orientation[ia],
                                          bar.cylinders[ib], reference_orientation[ib],
                                          bar.diameter, bar.steel));
  }
  return nodes;
}

}  // namespace rcdem
