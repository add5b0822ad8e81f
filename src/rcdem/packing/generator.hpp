#pragma once
// Concrete specimen generation, paper 2.3 and SPEC 2: aggregate spheres to the given mass
// content, mortar spheres until the target porosity, random positions, then relaxation.
#include "rcdem/io/scenario.hpp"
#include "rcdem/specimens/specimen_geometry.hpp"
#include "rcdem/state/particles.hpp"

namespace rcdem {

struct PackingReport {
  Real aggregate_volume = 0.0;    // sum of aggregate sphere volumes
  Real sphere_volume = 0.0;       // sum of all sphere volumes
  Real porosity = 0.0;            // 1 - sphere_volume / specimen volume
  Real min_distance_ratio = 0.0;  // min over pairs of |x_i - x_j| / min(r_i, r_j)
  Real min_face_ratio = 0.0;      // min over particles of distance to the boundary / r_i
};

Particles generate_packing(const GenerationSettings& settings, const SpecimenGeometry& geometry,
                           PackingReport* report = nullptr);

}  // namespace rcdem
