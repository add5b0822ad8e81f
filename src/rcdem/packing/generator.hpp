#pragma once
// Concrete specimen generation, paper 2.3 and SPEC 2: aggregate spheres to the given mass
// content, mortar spheres until the target porosity, random positions, then relaxation.
#include "rcdem/config/scenario.hpp"
#include "rcdem/config/specimen_geometry.hpp"
#include "rcdem/state/particles.hpp"

namespace rcdem {

struct PackingReport {
  Real aggregate_volume = 0.0;    // sum of aggregate sphere volumes
  Real sphere_volume = 0.0;       // sum of all sphere volumes
  Real porosity = 0.0;            // 1 - sphere_volume / specimen volume
  Real min_distance_ratio = 0.0;  // min over pairs of |x_i - x_j| / min(r_i, r_j)
  Real min_face_ratio = 0.0;      // min over particles of distance to the boundary / r_i
  Real min_bar_ratio = 0.0;       // min over particles of (distance to a bar axis - D/2) / r_i
};

// Concrete particles (aggregate, mortar), kept `bars` clear (SPEC 8): the bars' volume is not
// concrete, and no concrete centre lies within D/2 + min_distance_factor r of a bar's axis.
Particles generate_packing(const GenerationSettings& settings, const SpecimenGeometry& geometry,
                           PackingReport* report = nullptr,
                           const std::vector<BarSettings>& bars = {});

}  // namespace rcdem
