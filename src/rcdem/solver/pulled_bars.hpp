#pragma once
// Bars pulled out by their first cylinder (pull-out tests, bars.*.pull_velocity): the cylinder's
// velocity is prescribed along the bar, its rotation held; the force it takes is the pull-out load.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/archive.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/solver/loading_program.hpp"
#include "rcdem/solver/step_part.hpp"
#include "rcdem/specimens/specimen.hpp"

namespace rcdem {

struct PulledBar {
  std::string name;
  Index body = 0;
  Vec3 direction = Vec3::Zero();  // unit, end -> start
  Real speed = 0.0, ramp_time = 0.0;
  LoadingProgram motion{0.0, 0.0};  // pull_velocity after the ramp, or its program
  Real displacement = 0.0;          // along direction
  Vec3 force = Vec3::Zero();        // on the cylinder from the concrete and the rest of the bar
  Real work = 0.0;
  Real last_step = 0.0;
  Real load() const { return -force.dot(direction); }
  // From now on a constant speed along `direction` (leaving any program), reached over the ramp
  // time from t = 0 as at the start: once that has passed, the change is immediate.
  void set_speed(Real v) {
    speed = v;
    motion = LoadingProgram(v, ramp_time);
  }
};

// The pulled bars as a part of the step (solver/step_part.hpp): each prescribes its first
// cylinder's velocity over the next move, and after it books the driver's work.
struct PulledBars final : StepPart {
  std::vector<PulledBar> bars;
  std::vector<std::size_t> slot;  // per bar: its entry in the prescribed motion
  std::vector<Real> force_prev;   // per bar: the driver's force at the last step (its work)

  // The scenario's pulled bars, whose first cylinders it claims in `motion`.
  PulledBars(const Scenario& sc, const Specimen& specimen, PrescribedMotion& motion);
  const PulledBar* find(const std::string& name) const;

  void prescribe(PrescribedMotion& motion, const StepClock& clock) override;
  void drive(const Bodies& bodies, const StepClock& clock, Energy& ledger) override;

  // The checkpoint's "pulled_bars" (core/archive.hpp).
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& s) {
    ar.table("pulled_bars", s.bars.size(),
             column("displacement", "m", s.bars, &PulledBar::displacement),
             column("force", "N", s.bars, &PulledBar::force),
             column("work", "J", s.bars, &PulledBar::work),
             column("last_step", "m", s.bars, &PulledBar::last_step),
             column("force_prev", "N", s.force_prev));
    // Only where a bar has a program (the runs without one keep their format).
    const bool programs = std::any_of(s.bars.begin(), s.bars.end(), [](const PulledBar& b) {
      return b.motion.explicit_program();
    });
    if (programs)
      ar.table(
          "pulled_bar_programs", s.bars.size(),
          column_of(
              "program", "", [&](std::size_t i) -> auto& { return s.bars[i].motion.state(); }));
  }
};

}  // namespace rcdem
