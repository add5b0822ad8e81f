#include "rcdem/packing/space_filling_order.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

namespace rcdem {

namespace {

// Spreads the low 21 bits of v so that bit k lands on bit 3k.
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffffULL;
  v = (v | (v << 32)) & 0x1f00000000ffffULL;
  v = (v | (v << 16)) & 0x1f0000ff0000ffULL;
  v = (v | (v << 8)) & 0x100f00f00f00f00fULL;
  v = (v | (v << 4)) & 0x10c30c30c30c30c3ULL;
  v = (v | (v << 2)) & 0x1249249249249249ULL;
  return v;
}

}  // namespace

std::uint64_t morton_key(const Vec3& x, const Vec3& lo, const Vec3& hi) {
  constexpr double kCells = 2097151.0;  // 2^21 - 1
  // One scale for all axes, so that the curve's cells are cubes even in a long beam.
  const double extent = (hi - lo).maxCoeff();
  std::uint64_t key = 0;
  for (int k = 0; k < 3; ++k) {
    double t = extent > 0.0 ? (x[k] - lo[k]) / extent : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    key |= spread_bits(static_cast<std::uint64_t>(t * kCells)) << k;
  }
  return key;
}

void sort_along_morton_curve(Particles& p, const Vec3& lo, const Vec3& hi) {
  const auto n = static_cast<std::size_t>(p.size());
  std::vector<std::uint64_t> key(n);
  for (std::size_t i = 0; i < n; ++i) key[i] = morton_key(p.position[i], lo, hi);
  std::vector<Index> order(n);
  std::iota(order.begin(), order.end(), Index{0});
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return key[a] < key[b]; });
  Particles sorted;
  for (Index i : order) sorted.add(p.position[i], p.radius[i], p.kind[i]);
  if (!p.cell_volume.empty())
    for (Index i : order) sorted.cell_volume.push_back(p.cell_volume[i]);
  p = std::move(sorted);
}

}  // namespace rcdem
