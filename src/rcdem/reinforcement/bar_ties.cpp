#include "rcdem/reinforcement/bar_ties.hpp"

#include <algorithm>
#include <numeric>
#include <utility>

#include "rcdem/config/bar_path.hpp"
#include "rcdem/core/segment_distance.hpp"

namespace rcdem {

namespace {

struct TouchingPair {
  Index a, b;
  Vec3 point_a, point_b;
};

// Whether cylinders x and y of `bar` are the same or joined by a node.
bool joined(const Bar& bar, Index x, Index y) {
  if (x == y) return true;
  return std::any_of(bar.nodes.begin(), bar.nodes.end(), [&](const auto& n) {
    return (n[0] == x && n[1] == y) || (n[0] == y && n[1] == x);
  });
}

std::vector<TouchingPair> touching_pairs(const Bar& a, const Bar& b) {
  const Real radii = 0.5 * (a.diameter + b.diameter);
  const Real tolerance = bar_touch_tolerance(a.diameter, b.diameter);
  std::vector<TouchingPair> out;
  const auto ends = [](const CylinderGeometry& c) {
    return std::pair<Vec3, Vec3>{c.centre - 0.5 * c.length * c.axis, c.centre + 0.5 * c.length * c.axis};
  };
  for (std::size_t i = 0; i < a.cylinders.size(); ++i) {
    const auto [a0, a1] = ends(a.cylinders[i]);
    for (std::size_t j = 0; j < b.cylinders.size(); ++j) {
      const auto [b0, b1] = ends(b.cylinders[j]);
      const SegmentClosestPoints c = closest_points(a0, a1, b0, b1);
      if (c.distance <= radii + tolerance && c.distance > 0.0)
        out.push_back({static_cast<Index>(i), static_cast<Index>(j), a0 + c.s * (a1 - a0),
                       b0 + c.t * (b1 - b0)});
    }
  }
  return out;
}

// Groups of touching pairs: two pairs are in one group where both their cylinders are the same or
// neighbours on each bar (a stirrup's bend wrapping a bar touches it along several chords).
std::vector<std::vector<std::size_t>> runs(const Bar& a, const Bar& b,
                                           const std::vector<TouchingPair>& pairs) {
  std::vector<std::size_t> root(pairs.size());
  std::iota(root.begin(), root.end(), std::size_t{0});
  const auto find = [&](std::size_t x) {
    while (root[x] != x) x = root[x] = root[root[x]];
    return x;
  };
  for (std::size_t p = 0; p < pairs.size(); ++p)
    for (std::size_t q = p + 1; q < pairs.size(); ++q)
      if (joined(a, pairs[p].a, pairs[q].a) && joined(b, pairs[p].b, pairs[q].b))
        root[find(q)] = find(p);
  std::vector<std::vector<std::size_t>> groups;
  std::vector<std::ptrdiff_t> group_of(pairs.size(), -1);
  for (std::size_t p = 0; p < pairs.size(); ++p) {  // pairs are in (a, b) order: so are groups
    auto& g = group_of[find(p)];
    if (g < 0) {
      g = static_cast<std::ptrdiff_t>(groups.size());
      groups.emplace_back();
    }
    groups[static_cast<std::size_t>(g)].push_back(p);
  }
  return groups;
}

// The group's pair nearest the mean of its contact points: the middle of a bend that wraps a
// bar (whatever the loop's numbering of its cylinders), the crossing of two straight bars.
const TouchingPair& middle(const std::vector<TouchingPair>& pairs,
                           const std::vector<std::size_t>& group) {
  const auto contact = [&](std::size_t p) { return 0.5 * (pairs[p].point_a + pairs[p].point_b); };
  Vec3 mean = Vec3::Zero();
  for (const std::size_t p : group) mean += contact(p);
  mean /= static_cast<Real>(group.size());
  std::size_t best = group.front();
  for (const std::size_t p : group)
    if ((contact(p) - mean).squaredNorm() < (contact(best) - mean).squaredNorm()) best = p;
  return pairs[best];
}

}  // namespace

std::vector<BarTie> find_bar_ties(const std::vector<Bar>& bars) {
  std::vector<BarTie> ties;
  for (std::size_t i = 0; i < bars.size(); ++i)
    for (std::size_t j = i + 1; j < bars.size(); ++j) {
      const std::vector<TouchingPair> pairs = touching_pairs(bars[i], bars[j]);
      for (const auto& group : runs(bars[i], bars[j], pairs)) {
        const TouchingPair& m = middle(pairs, group);
        ties.push_back({static_cast<int>(i), static_cast<int>(j), m.a, m.b, m.point_a, m.point_b});
      }
    }
  return ties;
}

InteractionNode make_tie_node(const BarTie& tie, const std::vector<Bar>& bars,
                              const Quat& reference_a, const Quat& reference_b) {
  const Bar& a = bars[static_cast<std::size_t>(tie.bar_a)];
  const Bar& b = bars[static_cast<std::size_t>(tie.bar_b)];
  const Bar& thinner = b.diameter < a.diameter ? b : a;
  return make_interaction_node_at(a.cylinders[static_cast<std::size_t>(tie.cylinder_a)],
                                  reference_a, tie.point_a,
                                  b.cylinders[static_cast<std::size_t>(tie.cylinder_b)],
                                  reference_b, tie.point_b, thinner.diameter, thinner.steel);
}

}  // namespace rcdem
