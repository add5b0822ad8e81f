#include "rcdem/solver/decomposition.hpp"

#include <algorithm>

#include "rcdem/core/error.hpp"

namespace rcdem {

namespace {

// The smallest multiple of `step` at or above x, at most `cap`.
Index round_up(Index x, Index step, Index cap) {
  return std::min(cap, (x + step - 1) / step * step);
}

// Offsets [0, ..., n] that split the items [0, n) into `ranks` ranges of about equal weight
// (prefix: weight before item i, size n + 1), each boundary a multiple of `step` (or n).
std::vector<Index> balanced_offsets(const std::vector<double>& prefix, Index step, int ranks) {
  const auto n = static_cast<Index>(prefix.size()) - 1;
  std::vector<Index> off(static_cast<std::size_t>(ranks) + 1, n);
  off[0] = 0;
  for (int r = 1; r < ranks; ++r) {
    const double target = prefix.back() * r / ranks;
    const auto it = std::lower_bound(prefix.begin(), prefix.end(), target);
    const Index i = round_up(static_cast<Index>(it - prefix.begin()), step, n);
    off[static_cast<std::size_t>(r)] = std::max(off[static_cast<std::size_t>(r) - 1], i);
  }
  return off;
}

}  // namespace

Decomposition Decomposition::build(const ContactNetwork& net, Index spheres, int rank, int ranks) {
  if (ranks < 1 || rank < 0 || rank >= ranks) fail("decomposition: rank {} of {}", rank, ranks);
  Decomposition d;
  d.rank = rank;
  d.ranks = ranks;
  const Index nc = net.contact_count();
  // The spheres by the local points of the contacts they lead (each contact's first particle).
  std::vector<double> body_points(static_cast<std::size_t>(spheres) + 1, 0.0);
  for (Index c = 0; c < nc; ++c)
    body_points[static_cast<std::size_t>(net.particle_a[c]) + 1] +=
        static_cast<double>(net.points_of(c));
  for (std::size_t i = 1; i < body_points.size(); ++i) body_points[i] += body_points[i - 1];
  d.sphere_offsets = balanced_offsets(body_points, kSphereBlock, ranks);
  // Each rank's contacts start with those its spheres lead, at the strain energy's block nearest.
  d.contact_offsets.assign(static_cast<std::size_t>(ranks) + 1, nc);
  d.contact_offsets[0] = 0;
  for (int r = 1; r < ranks; ++r) {
    const Index first = d.sphere_offsets[static_cast<std::size_t>(r)];
    const auto it = std::lower_bound(net.particle_a.begin(), net.particle_a.end(), first);
    const Index c = static_cast<Index>(it - net.particle_a.begin());
    const Index nearest = std::min(nc, (c + kEnergyBlock / 2) / kEnergyBlock * kEnergyBlock);
    d.contact_offsets[static_cast<std::size_t>(r)] =
        std::max(d.contact_offsets[static_cast<std::size_t>(r) - 1], nearest);
  }
  // Evaluated: the own contacts' blocks and every block with a contact of an own sphere.
  const Index blocks = (nc + kContactBlock - 1) / kContactBlock;
  std::vector<std::uint8_t> mark(static_cast<std::size_t>(blocks), 0);
  const auto r = static_cast<std::size_t>(rank);
  for (Index c = d.contact_offsets[r]; c < d.contact_offsets[r + 1]; ++c)
    mark[static_cast<std::size_t>(c / kContactBlock)] = 1;
  const Index lo = d.sphere_offsets[r], hi = d.sphere_offsets[r + 1];
  for (Index c = 0; c < nc; ++c) {
    const Index a = net.particle_a[c], b = net.particle_b[c];
    if ((a >= lo && a < hi) || (b >= lo && b < hi))
      mark[static_cast<std::size_t>(c / kContactBlock)] = 1;
  }
  for (Index k = 0; k < blocks; ++k)
    if (mark[static_cast<std::size_t>(k)]) d.evaluated_blocks.push_back(k);
  return d;
}

Index Decomposition::evaluated_points(const ContactNetwork& net) const {
  Index points = 0;
  for (const Index b : evaluated_blocks) {
    const Index end = std::min(net.contact_count(), (b + 1) * kContactBlock);
    points += net.point_begin[end] - net.point_begin[b * kContactBlock];
  }
  return points;
}

std::vector<Index> Decomposition::in_blocks(const std::vector<Index>& offsets, Index block) {
  std::vector<Index> out(offsets.size());
  for (std::size_t r = 0; r < out.size(); ++r) out[r] = (offsets[r] + block - 1) / block;
  return out;
}

}  // namespace rcdem
