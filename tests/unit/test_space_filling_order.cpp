// Particle numbering along the Morton curve (packing/space_filling_order): the renumbering is a
// permutation of the particles with their radii and kinds, in non-decreasing key order, and
// particles that are neighbours in space end up closer in memory than in generation order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "rcdem/core/rng.hpp"
#include "rcdem/packing/space_filling_order.hpp"

using namespace rcdem;

TEST(SpaceFillingOrder, MortonKeyInterleavesTheAxes) {
  const Vec3 lo(0, 0, 0), hi(1, 1, 1);
  EXPECT_EQ(morton_key(lo, lo, hi), 0u);
  // The top cell of each axis alone: its 21 bits at positions k, k + 3, ...
  const std::uint64_t x = morton_key(Vec3(1, 0, 0), lo, hi);
  const std::uint64_t y = morton_key(Vec3(0, 1, 0), lo, hi);
  const std::uint64_t z = morton_key(Vec3(0, 0, 1), lo, hi);
  EXPECT_EQ(x, 0x1249249249249249ULL & ((1ULL << 63) - 1));
  EXPECT_EQ(y, x << 1);
  EXPECT_EQ(z, x << 2);
  EXPECT_EQ(morton_key(hi, lo, hi), x | y | z);
  // Outside the box: clamped.
  EXPECT_EQ(morton_key(Vec3(2, -1, 0.5), lo, hi), morton_key(Vec3(1, 0, 0.5), lo, hi));
}

TEST(SpaceFillingOrder, RenumberingIsAPermutationInKeyOrderThatBringsNeighboursTogether) {
  Rng rng(3);
  const Vec3 lo(0, 0, 0), hi(0.7, 0.15, 0.1);
  Particles p;
  for (int i = 0; i < 4000; ++i)
    p.add(Vec3(0.7 * rng.uniform(), 0.15 * rng.uniform(), 0.1 * rng.uniform()),
          0.001 + 0.001 * rng.uniform(),
          i % 5 == 0 ? ParticleKind::Aggregate : ParticleKind::Mortar);
  const Particles before = p;
  sort_along_morton_curve(p, lo, hi);
  ASSERT_EQ(p.size(), before.size());
  using Row = std::tuple<Real, Real, Real, Real, int>;
  const auto rows = [](const Particles& q) {
    std::vector<Row> r;
    for (Index i = 0; i < q.size(); ++i)
      r.emplace_back(q.position[i].x(), q.position[i].y(), q.position[i].z(), q.radius[i],
                     static_cast<int>(q.kind[i]));
    std::sort(r.begin(), r.end());
    return r;
  };
  EXPECT_EQ(rows(p), rows(before));  // the same particles, each with its radius and kind
  for (Index i = 1; i < p.size(); ++i)
    ASSERT_LE(morton_key(p.position[i - 1], lo, hi), morton_key(p.position[i], lo, hi));
  // Consecutive particles: far closer in space than in the random generation order.
  const auto mean_step = [](const Particles& q) {
    Real s = 0;
    for (Index i = 1; i < q.size(); ++i) s += (q.position[i] - q.position[i - 1]).norm();
    return s / static_cast<Real>(q.size() - 1);
  };
  EXPECT_LT(mean_step(p), 0.2 * mean_step(before));
  // Deterministic.
  Particles again = before;
  sort_along_morton_curve(again, lo, hi);
  EXPECT_EQ(again.position, p.position);
}
