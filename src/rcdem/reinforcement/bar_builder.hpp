#pragma once
// A straight steel bar cut into rigid cylinders joined by interaction nodes (paper 2.5, SPEC 7).
#include <array>
#include <vector>

#include "rcdem/core/types.hpp"
#include "rcdem/reinforcement/interaction_node.hpp"
#include "rcdem/reinforcement/rigid_cylinder.hpp"
#include "rcdem/state/bodies.hpp"

namespace rcdem {

inline constexpr Real kDefaultCylinderLength = 0.032;  // paper 3: 32 mm cylinders

struct Bar {
  Real diameter;
  SteelMaterial steel;
  std::vector<CylinderGeometry> cylinders;  // from the start point to the end point
  std::vector<std::array<Index, 2>> nodes;  // (A, B) = (i, i + 1), indices into `cylinders`
};

// The bar from `start` to `end` cut into n = round(length / target_cylinder_length) (at least 1)
// equal cylinders, all with the axis start -> end. Fails (rcdem::fail) for D <= 0, a bar shorter
// than D, a non-positive target length, or a steel with non-physical constants.
Bar build_straight_bar(const Vec3& start, const Vec3& end, Real diameter,
                       const SteelMaterial& steel,
                       Real target_cylinder_length = kDefaultCylinderLength);

// A bent bar along the centreline `points` (config/bar_path.hpp): each chord cut into
// round(length / target_cylinder_length) (at least 1) equal cylinders along it, a node between
// consecutive cylinders (a kinked one at a bend), and for a loop (`closed`) a node joining the
// last cylinder to the first. Fails as build_straight_bar does.
Bar build_polyline_bar(const std::vector<Vec3>& points, bool closed, Real diameter,
                       const SteelMaterial& steel,
                       Real target_cylinder_length = kDefaultCylinderLength);

// The nodes' constants, with the orientations the solver holds for the cylinders at t = 0
// (identity when it stores rotations since t = 0; orientation_for_axis() when it stores
// body-to-world rotations).
std::vector<InteractionNode> make_bar_nodes(const Bar& bar,
                                            const std::vector<Quat>& reference_orientation);

}  // namespace rcdem
