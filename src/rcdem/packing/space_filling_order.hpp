#pragma once
// Particle numbering along a space-filling curve (Morton, Z-order), so that particles near each
// other in space are near each other in memory. The contact loop reads both particles of every
// contact; with the generator's random numbering those reads missed the cache (a quarter of the
// contact loop's time went to waiting for body positions), with this order they mostly hit.
#include <cstdint>

#include "rcdem/state/particles.hpp"

namespace rcdem {

// The Morton key of x in the box [lo, hi] scaled to its longest side: 21 bits per axis,
// interleaved (x lowest).
std::uint64_t morton_key(const Vec3& x, const Vec3& lo, const Vec3& hi);

// Renumbers the particles in increasing Morton key (ties keep their order: deterministic).
void sort_along_morton_curve(Particles& particles, const Vec3& lo, const Vec3& hi);

}  // namespace rcdem
