#include "rcdem/config/scenario_checks.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "rcdem/config/bar_path.hpp"
#include "rcdem/config/specimen_geometry.hpp"
#include "rcdem/config/specimen_registry.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/segment_distance.hpp"

namespace rcdem::config {

std::string key_location(const Scenario& s, const std::string& key) {
  const auto it = s.key_line.find(key);
  return it == s.key_line.end() ? s.source.string()
                                : fmt::format("{}:{}", s.source.string(), it->second);
}

namespace {

// The concrete particles a specimen will hold, estimated from its solid volume and mean size.
double estimated_concrete_particles(const Scenario& s) {
  const auto& g = s.generation;
  const Real solid = (1.0 - g.porosity) * specimen_geometry(s).volume();
  const Real mean_diameter = 0.5 * (std::min(g.aggregate_d_min, g.mortar_d_min) + g.mortar_d_max);
  return solid / (kPi / 6.0 * std::pow(mean_diameter, 3));
}

double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

// The key that sets a bar's count of interface spheres: sphere_spacing, or D / 2 by default.
std::string spacing_key(const BarSettings& b) {
  return "bars." + b.name + (b.sphere_spacing > 0.0 ? ".sphere_spacing" : ".diameter");
}

}  // namespace

void check_model_size(const Scenario& s) {
  const double limit = static_cast<double>(s.generation.max_particles);
  const double concrete = estimated_concrete_particles(s);
  if (concrete > limit)
    fail(
        "{}: key 'specimen.size': the specimen would hold about {:.3g} particles, more than "
        "generation.max_particles = {}; raise that limit if this is intended",
        key_location(s, "specimen.size"), concrete, s.generation.max_particles);
  double bodies = concrete;
  for (const auto& b : s.bars) {
    const double length = b.length();
    const double cylinders = std::max(1.0, std::round(length / b.cylinder_length));
    const double spheres = std::max(cylinders, length / b.spacing());
    if (cylinders > limit)
      fail(
          "{}: key 'bars.{}.cylinder_length' = {} m cuts the {} m bar into about {:.3g} "
          "cylinders, more than generation.max_particles = {}",
          key_location(s, "bars." + b.name + ".cylinder_length"), b.name, b.cylinder_length, length,
          cylinders, s.generation.max_particles);
    bodies += spheres + cylinders;
    if (bodies > limit)
      fail(
          "{}: key '{}': bar '{}' would carry about {:.3g} interface spheres ({} m long, {} m "
          "apart), making {:.3g} bodies with the concrete: more than "
          "generation.max_particles = {}",
          key_location(s, spacing_key(b)), spacing_key(b), b.name, spheres, length, b.spacing(),
          bodies, s.generation.max_particles);
  }
  const double need = bodies * kBytesPerParticle, have = physical_memory_bytes();
  if (have > 0.0 && need > have)
    fail(
        "{}: key 'specimen.size': about {:.3g} bodies would need about {:.1f} GiB, more than "
        "this machine's {:.1f} GiB of memory",
        key_location(s, "specimen.size"), bodies, need / (1u << 30), have / (1u << 30));
}

namespace {

// The shortest distance from segment a-b to the notch's slot, which spans the whole width (y):
// distance to a convex set along a line is convex in the line's parameter, so a ternary search
// finds its minimum.
Real distance_to_notch(const Vec3& a, const Vec3& b, const SpecimenGeometry& g) {
  const auto to_slot = [&](Real t) {
    const Vec3 p = a + t * (b - a);
    const Real dx = std::max(0.0, std::abs(p.x() - g.notch.x_center) - 0.5 * g.notch.width);
    const Real dz = std::max({0.0, p.z() - (g.lo.z() + g.notch.depth), g.lo.z() - p.z()});
    return std::hypot(dx, dz);
  };
  Real lo = 0.0, hi = 1.0;
  for (int i = 0; i < 100; ++i) {
    const Real m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    if (to_slot(m1) <= to_slot(m2))
      hi = m2;
    else
      lo = m1;
  }
  return std::min({to_slot(0.0), to_slot(1.0), to_slot(0.5 * (lo + hi))});
}

}  // namespace

void check_bar_layout(const Scenario& s) {
  if (static_cast<int>(s.bars.size()) > kMaxBars)
    fail("{}: {} bars: expected at most {}", key_location(s, "bars." + s.bars.back().name),
         s.bars.size(), kMaxBars);
  for (std::size_t i = 0; i < s.bars.size(); ++i)
    for (std::size_t j = i + 1; j < s.bars.size(); ++j) {
      const auto &a = s.bars[i], &b = s.bars[j];
      Real gap = std::numeric_limits<Real>::infinity();
      for (const auto& [a0, a1] : a.chords())
        for (const auto& [b0, b1] : b.chords()) gap = std::min(gap, closest_points(a0, a1, b0, b1).distance);
      const Real radii = 0.5 * (a.diameter + b.diameter);
      const Real tolerance = bar_touch_tolerance(a.diameter, b.diameter);
      if (gap < radii - tolerance)
        fail(
            "{}: bars '{}' and '{}' overlap: their axes come {:.4g} m close, less than the sum "
            "of their radii ({:.4g} m) less {:.2g} m; expected separate bars, or touching ones "
            "(axes {:.4g} m apart, within {:.2g} m), which are tied (move or thin one of them)",
            key_location(s, "bars." + b.name + (b.bent() ? ".path" : ".start")), a.name, b.name,
            gap, radii, tolerance, radii, tolerance);
    }
  const SpecimenGeometry g = specimen_geometry(s);
  if (!g.notch.present()) return;
  for (const auto& b : s.bars) {
    Real gap = std::numeric_limits<Real>::infinity();
    for (const auto& [b0, b1] : b.chords()) gap = std::min(gap, distance_to_notch(b0, b1, g));
    if (gap < 0.5 * b.diameter)
      fail(
          "{}: bar '{}' cuts through the notch (specimen.notch_depth = {} m): its axis comes "
          "{:.4g} m close to the slot, less than its radius ({:.4g} m); expected the bar above "
          "the notch",
          key_location(s, "bars." + b.name + ".start"), b.name, s.specimen.notch_depth, gap,
          0.5 * b.diameter);
  }
}

void check_plate_layout(const Scenario& s) {
  if (static_cast<int>(s.plates.size()) > kMaxPlates)
    fail("{}: {} plates: expected at most {}", key_location(s, "plates." + s.plates.back().name),
         s.plates.size(), kMaxPlates);
  for (std::size_t i = 0; i < s.plates.size(); ++i)
    for (std::size_t j = i + 1; j < s.plates.size(); ++j) {
      const auto &a = s.plates[i], &b = s.plates[j];
      if (a.axis != b.axis || a.side != b.side) continue;
      const auto ra = a.rectangle(s.specimen.size), rb = b.rectangle(s.specimen.size);
      const bool overlap = std::min(ra[1], rb[1]) > std::max(ra[0], rb[0]) &&
                           std::min(ra[3], rb[3]) > std::max(ra[2], rb[2]);
      if (overlap)
        fail(
            "{}: plates '{}' and '{}' overlap on the face {}{}: expected one plate per part of "
            "a face (give each an extent that the other does not cover)",
            key_location(s, "plates." + b.name + ".face"), a.name, b.name,
            static_cast<char>('x' + a.axis), a.side < 0 ? '-' : '+');
    }
}

}  // namespace rcdem::config
