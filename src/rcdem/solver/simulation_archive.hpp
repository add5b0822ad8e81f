#pragma once
// Simulation::serialize (core/archive.hpp): every part of the state a step changes, each part's
// sections written by the part itself, in the checkpoint file's order (docs/checkpoint.md).
#include "rcdem/solver/simulation.hpp"

namespace rcdem {

template <class Archive, class Self>
void Simulation::serialize(Archive& ar, Self& s) {
  Bodies::serialize(ar, s.bodies_);
  BodyStepSums::serialize(ar, s.step_sums_);
  ContactState::serialize(ar, "contacts", s.concrete_.contacts);
  BarSystem::serialize(ar, s.bars_);
  PlateSet::serialize(ar, s.plates_);
  PulledBars::serialize(ar, s.pulled_);
  auto& e = s.energy_;
  ar.record("solver", s.time_, s.steps_, s.time_step_.dt, s.damping_, e.external_work, e.strain,
            e.kinetic, e.damage, e.friction, e.damping, e.plastic);
  LoadingRate::serialize(ar, s.loading_rate_);
  // Restored: which contacts are intact follows from the points' damage, and none is condensed
  // (their histories were complete when saved).
  if constexpr (Archive::loading)
    if (ar.applying() && !s.concrete_.condensation.sums.empty())
      s.concrete_.condensation.reset_flags(s.specimen_.contacts,
                                           s.concrete_.contacts.point.damage());
}

}  // namespace rcdem
