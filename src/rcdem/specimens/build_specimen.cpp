#include <algorithm>
#include <cmath>

#include "rcdem/config/specimen_registry.hpp"
#include "rcdem/packing/space_filling_order.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "rcdem/tessellation/cell_complex.hpp"

namespace rcdem {

namespace {

// The interface spheres of one cylinder (SPEC 8): diameter D, about `spacing` apart along its
// axis, evenly filling its length.
void add_interface_spheres(const CylinderGeometry& cyl, Real diameter, Real spacing, int bar,
                           Index body, Particles& particles, SteelSpheres& steel) {
  const auto n = std::max<Index>(1, static_cast<Index>(std::llround(cyl.length / spacing)));
  for (Index k = 0; k < n; ++k) {
    const Real s =
        (static_cast<Real>(k) + 0.5) * cyl.length / static_cast<Real>(n) - 0.5 * cyl.length;
    particles.add(cyl.centre + s * cyl.axis, 0.5 * diameter, ParticleKind::Steel);
    steel.bar.push_back(bar);
    steel.body.push_back(body);
  }
}

}  // namespace

Specimen build_specimen(const Scenario& scenario) {
  Specimen s;
  s.geometry = specimen_geometry(scenario);
  for (const auto& b : scenario.bars) {
    const SteelMaterial steel{b.E, b.nu, b.f_y, b.density};
    s.bars.push_back(b.bent() ? build_polyline_bar(b.axis, b.closed, b.diameter, steel,
                                                   b.cylinder_length)
                              : build_straight_bar(b.start, b.end, b.diameter, steel,
                                                   b.cylinder_length));
  }
  s.ties = find_bar_ties(s.bars);
  s.particles = generate_packing(scenario.generation, s.geometry, &s.packing, scenario.bars);
  sort_along_morton_curve(s.particles, s.geometry.lo, s.geometry.hi);
  s.concrete_count = s.particles.size();
  s.steel.first = s.concrete_count;
  Index body = s.concrete_count;
  for (std::size_t k = 0; k < s.bars.size(); ++k)
    for (const auto& cyl : s.bars[k].cylinders)
      add_interface_spheres(cyl, s.bars[k].diameter, scenario.bars[k].spacing(),
                            static_cast<int>(k), body++, s.particles, s.steel);
  const CellComplex cells = tessellate(s.particles, s.geometry, scenario.tessellation);
  s.particles.cell_volume = cells.volume;
  s.contacts = build_contact_network(s.particles, cells, s.geometry, scenario.contact, &s.network,
                                     &s.boundary);
  if (!s.bars.empty())
    s.interfaces =
        build_interface_contacts(s.particles, cells, s.steel, scenario.bars, scenario.contact);
  return s;
}

}  // namespace rcdem
