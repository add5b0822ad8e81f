#pragma once
// Ties where two bars touch (issue 41, item 4): a stirrup wired or welded to the longitudinal bar
// it wraps. Rule (docs/model.md 14): two bars touch where their axes come within the sum of their
// radii, plus or minus config/bar_path.hpp's tolerance; each run of touching cylinder pairs gets
// one tie, at its middle pair (the one nearest the run's mean contact point), joining the two
// cylinders at the closest points of their axes by an interaction node of the thinner bar
// (reinforcement/interaction_node.hpp: make_interaction_node_at).
#include <vector>

#include "rcdem/core/types.hpp"
#include "rcdem/reinforcement/bar_builder.hpp"

namespace rcdem {

struct BarTie {
  int bar_a, bar_b;              // bar_a < bar_b, indices into the specimen's bars
  Index cylinder_a, cylinder_b;  // indices into each bar's cylinders
  Vec3 point_a, point_b;         // the closest points of the two cylinders' axes at t = 0
};

// Every tie between `bars`, in the order of (bar_a, bar_b), then of (cylinder_a, cylinder_b).
std::vector<BarTie> find_bar_ties(const std::vector<Bar>& bars);

// The tie's node: the thinner bar's springs (9) between the two cylinders' material points at
// the tie, its axis the line between the two axes (the tie's axial spring resists their
// separation, its shear spring their sliding along each other). The references are the two
// cylinders' orientations at t = 0 as the solver holds them (reinforcement/bar_builder.hpp).
InteractionNode make_tie_node(const BarTie& tie, const std::vector<Bar>& bars,
                              const Quat& reference_a, const Quat& reference_b);

}  // namespace rcdem
