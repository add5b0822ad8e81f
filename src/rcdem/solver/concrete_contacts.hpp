#pragma once
// What the step keeps for the concrete network besides the specimen: its law, every local point's
// history, the condensation of intact contacts, the body -> contacts index for the gather, and the
// kinematics of the last two evaluations, which a condensed contact's catch-up reads
// (contact_loop.hpp, evaluate_contacts).
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/contact/contact_state.hpp"
#include "rcdem/contact/elastic_condensation.hpp"
#include "rcdem/contact/laws/law_registry.hpp"
#include "rcdem/solver/body_contacts.hpp"
#include "rcdem/state/bodies.hpp"
#include "rcdem/state/body_poses.hpp"

namespace rcdem {

struct ConcreteContacts {
  ContactLaw law;  // contact.law
  // Mutable: condensed contacts' point histories are filled in when first read (logically const).
  mutable ContactState contacts;
  mutable ElasticCondensation condensation;  // empty when off or for a law that does not opt in
  BodyContacts body_contacts;
  // The bodies' centres at the last evaluation and the one before, and their orientations as
  // matrices (formed at the start of each step; derived: not part of a checkpoint).
  std::vector<Vec3> position_eval, position_prev;
  std::vector<Eigen::Matrix3d> rotation, rotation_prev;
  BodyPoses pose;  // the same with the centres, for the condensed contacts' kernel
  mutable std::vector<Real> strain_energy_blocks;  // the strain energy's per-block sums

  // For the network `net` of the specimen whose bodies are `bodies` (at t = 0).
  static ConcreteContacts build(const Scenario& sc, const ContactNetwork& net,
                                const Bodies& bodies);
};

}  // namespace rcdem
