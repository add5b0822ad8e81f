#pragma once
// How a distributed run (docs/parallel.md) shares the step among its ranks, fixed at the set-up
// from the contact network alone, so that every rank computes the same one:
//
//   spheres    rank r integrates the concrete particles [sphere_offsets[r], sphere_offsets[r+1]),
//              whole blocks of the integrator's (BodyStepSums::kSphereBlock), and every rank
//              integrates every bar cylinder (they are few; their forces come from parts every
//              rank evaluates whole);
//   contacts   rank r owns the concrete contacts [contact_offsets[r], contact_offsets[r+1]),
//              whole blocks of the strain energy's sums (kEnergyBlock, itself whole blocks of the
//              contact loop's): the transitions, crack log, dissipation and strain energy of those
//              blocks are its to report;
//   evaluated  the contact loop's blocks rank r evaluates: its own, and every block with a contact
//              of one of its spheres (a contact on the cut between two ranks is evaluated by
//              both, from the same poses and histories, so with the same bits).
//
// The spheres are numbered along a space-filling curve and the contacts by their first particle,
// so a range of each is a compact region and the extra blocks are its surface. The ranges balance
// the local points (each contact counted with its first particle), the loop's work.
#include <vector>

#include "rcdem/contact/elastic_condensation.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/solver/body_step_sums.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

struct Decomposition {
  static constexpr Index kContactBlock = CondensedBlock::kSize;  // the contact loop's
  static constexpr Index kEnergyBlock = 1024;  // ConcreteContacts' strain energy sums
  static constexpr Index kSphereBlock = BodyStepSums::kSphereBlock;  // the integrator's

  int rank = 0, ranks = 1;
  std::vector<Index> sphere_offsets;    // ranks + 1 entries
  std::vector<Index> contact_offsets;   // ranks + 1 entries
  std::vector<Index> evaluated_blocks;  // this rank's, ascending

  // For `spheres` concrete particles (bodies [0, spheres)) and their network.
  static Decomposition build(const ContactNetwork& net, Index spheres, int rank, int ranks);

  // `offsets` in units of `block` (each offset a multiple of it, the last one rounded up).
  static std::vector<Index> in_blocks(const std::vector<Index>& offsets, Index block);
  // The local points of this rank's evaluated blocks (its share of the loop's work, the cut's
  // blocks included).
  Index evaluated_points(const ContactNetwork& net) const;
};

}  // namespace rcdem
