#include "rcdem/config/specimen_registry.hpp"

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/error.hpp"

namespace rcdem {

namespace {

SpecimenGeometry box_geometry(const Scenario& s) {
  SpecimenGeometry g;
  g.hi = s.specimen.size;
  return g;
}

SpecimenGeometry beam_geometry(const Scenario& s) {
  SpecimenGeometry g = box_geometry(s);
  if (s.specimen.notch_depth > 0.0) {
    g.notch.x_center = 0.5 * s.specimen.size.x();
    g.notch.width = s.specimen.notch_width;
    g.notch.depth = s.specimen.notch_depth;
  }
  return g;
}

}  // namespace

const std::vector<SpecimenBuilder>& specimen_builders() {
  static const std::vector<SpecimenBuilder> builders = {
      {"box", "axis-aligned box, e.g. the 160 mm cube of the uniaxial tests", box_geometry},
      {"beam", "prismatic beam along x, depth along z, optional central notch", beam_geometry},
  };
  return builders;
}

const SpecimenBuilder& find_specimen_builder(const std::string& name) {
  for (const auto& b : specimen_builders())
    if (b.name == name) return b;
  fail("unknown specimen shape '{}'", name);
}

void validate_specimen(const Scenario& s) {
  const SpecimenGeometry g = find_specimen_builder(s.specimen.shape).geometry(s);
  if (g.notch.present() && g.notch.width >= 0.5 * g.size().x()) {
    const auto it = s.key_line.find("specimen.notch_width");
    const std::string at = it == s.key_line.end()
                               ? s.source.string() + " (default value)"
                               : fmt::format("{}:{}", s.source.string(), it->second);
    fail("{}: key 'specimen.notch_width' ({} m) must be less than half the beam length", at,
         g.notch.width);
  }
}

SpecimenGeometry specimen_geometry(const Scenario& s) {
  return find_specimen_builder(s.specimen.shape).geometry(s);
}

}  // namespace rcdem
