#pragma once
// The spherical particles, as a structure of arrays (one array per quantity) so that hot loops
// stream only what they read and a GPU back end can take raw pointers.
#include <cstdint>
#include <vector>

#include "rcdem/core/types.hpp"

namespace rcdem {

enum class ParticleKind : std::int32_t { Aggregate = 0, Mortar = 1, Steel = 2 };

struct Particles {
  std::vector<Vec3> position;
  std::vector<Real> radius;
  std::vector<ParticleKind> kind;
  std::vector<Real> cell_volume;  // volume of the particle's (clipped) Voronoi cell

  Index size() const { return static_cast<Index>(position.size()); }
  void add(const Vec3& x, Real r, ParticleKind k) {
    position.push_back(x);
    radius.push_back(r);
    kind.push_back(k);
  }
  Index count(ParticleKind k) const {
    Index n = 0;
    for (auto kk : kind) n += (kk == k);
    return n;
  }
};

}  // namespace rcdem
