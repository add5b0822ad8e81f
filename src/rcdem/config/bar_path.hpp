#pragma once
// A bent bar's centreline (issue 41, item 4): the polyline through its corner points with every
// corner rounded by an arc of the bend radius, the arcs cut into chords of at most `max_turn` each.
// The bar's cylinders lie along these chords, and its interaction nodes join them at the kinks
// (the nodes' model is the same along any polyline: reinforcement/interaction_node.hpp).
#include <string>
#include <vector>

#include "rcdem/core/types.hpp"

namespace rcdem {

inline constexpr Real kMaxBendChordTurn = 0.5235987755982988;  // 30 degrees per chord of a bend

// Two bars touch, and are tied where they do (reinforcement/bar_ties.hpp), where their axes come
// within the sum of their radii plus or minus this fraction of the thinner bar's diameter: a
// stirrup drawn round a bar at exactly r_a + r_b touches it although the chords of its bends cut
// a little inside the arc (a 30-degree chord of radius R by 0.034 R). Closer is an overlap.
inline constexpr Real kBarTouchTolerance = 0.1;
inline Real bar_touch_tolerance(Real diameter_a, Real diameter_b) {
  return kBarTouchTolerance * (diameter_a < diameter_b ? diameter_a : diameter_b);
}

// The centreline's points in order. Open: from the first corner point to the last. Closed: a loop
// (every point a rounded corner), its first point not repeated at the end. Fails naming `where`
// where two corner points coincide or a bend's arc does not fit between its neighbours.
std::vector<Vec3> bar_centreline(const std::vector<Vec3>& corners, bool closed, Real radius,
                                 const std::string& where, Real max_turn = kMaxBendChordTurn);

}  // namespace rcdem
