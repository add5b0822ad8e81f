#pragma once
// Simulation::serialize (core/archive.hpp): every part of the state a step changes, each part's
// sections written by the part itself, in the checkpoint file's order (docs/checkpoint.md).
#include <type_traits>
#include <utility>

#include "rcdem/core/archive.hpp"
#include "rcdem/solver/simulation.hpp"

namespace rcdem {

template <class Archive, class Self>
void Simulation::serialize(Archive& ar, Self& s) {
  Bodies::serialize(ar, s.bodies_);
  Integrator::serialize(ar, s.integrator_);
  ConcreteContacts::serialize(ar, s.concrete_);
  for (auto& bar : s.interfaces_) {
    if constexpr (std::is_const_v<Self>)
      BarInterface::serialize(ar, std::as_const(*bar));
    else
      BarInterface::serialize(ar, *bar);
  }
  InteractionNodes::serialize(ar, s.nodes_);
  PlateSet::serialize(ar, s.plates_);
  PulledBars::serialize(ar, s.pulled_);
  InteractionNodes::serialize(ar, s.ties_);
  auto& e = s.energy_;
  ar.record("solver", named("time", "s", s.time_), named("steps", "-", s.steps_),
            named("time_step", "s", s.time_step_.dt),
            named("damping", "1", s.integrator_.damping_ref()),
            named("external_work", "J", e.external_work), named("strain", "J", e.strain),
            named("kinetic", "J", e.kinetic), named("damage", "J", e.damage),
            named("friction", "J", e.friction), named("damping_work", "J", e.damping),
            named("plastic", "J", e.plastic));
  LoadingRate::serialize(ar, s.loading_rate_);
  // Restored, every rank holds the whole state the file held: nothing to gather at this step.
  if constexpr (!std::is_const_v<Self>) s.motion_step_ = s.steps_;
}

}  // namespace rcdem
