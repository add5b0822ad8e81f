#pragma once
// The time step a simulation takes and how it was chosen (SPEC 6): the stable estimate, what set
// it, the assembly's omega_max when asked for, and the selective mass scaling applied.
#include <string>

#include "rcdem/core/types.hpp"
#include "rcdem/solver/critical_time_step.hpp"
#include "rcdem/solver/selective_mass_scaling.hpp"

namespace rcdem {

struct TimeStepChoice {
  Real dt = 0.0;                 // the step taken
  Real stable = 0.0;             // the estimate dt is a safety factor of
  std::string limit;             // which body and motion set it, in words
  CriticalTimeStep critical;     // solver.time_step_estimate = "assembled"
  MassScalingPlan mass_scaling;  // identity when off
};

}  // namespace rcdem
