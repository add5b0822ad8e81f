#pragma once
// What the integration leaves per body for the step's ledger (SPEC 11) and the instability check,
// and the concrete particles' sums of the same per block of kSphereBlock, formed while the block
// is in cache so that the ledger adds a few hundred numbers in a fixed order.
#include <cstdint>
#include <vector>

#include "rcdem/core/archive.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/state/bodies.hpp"

namespace rcdem {

struct BodyStepSums {
  static constexpr Index kSphereBlock = 128;
  struct Block {
    Real damping_work = 0.0, kinetic = 0.0;
    std::int64_t jumped = 0;
  };
  Index spheres = 0;  // bodies [0, spheres) are concrete particles (advance_spheres)
  std::vector<Real> damping_work, kinetic;
  std::vector<std::int64_t> jumped;
  std::vector<Block> blocks;  // per block of concrete particles

  // Sized for `bodies`; the concrete particles are the leading bodies with isotropic inertia
  // whose motion no part prescribes (driven: per body, >= 0 if one does).
  static BodyStepSums build(const Bodies& bodies, const std::vector<std::int64_t>& driven);

  // The checkpoint's "bodies.step" (core/archive.hpp); the blocks are summed again by a step.
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& s) {
    ar.table("bodies.step", s.kinetic.size(), column("damping_work", "J", s.damping_work),
             column("kinetic", "J", s.kinetic), column("jumped", "-", s.jumped));
  }
};

}  // namespace rcdem
