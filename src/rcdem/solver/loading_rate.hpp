#pragma once
// An adaptive loading rate (issue 26; docs/model.md 6): the prescribed plates and pulled bars
// move at factor x their set speed, the factor rising while the run is quasi-static by SPEC 6's
// own measure and falling back to 1 when it is not. Displacement stays the control variable: only
// how fast the plate gets there changes.
//
// The rule, checked every kCheckSteps steps from the energy ledger alone (no sweep over points):
// - not quasi-static: the kinetic energy above `kinetic_ratio` x the strain energy, or a crack
//   burst, more than `damage_work_ratio` of the work done since the last check dissipated by
//   damage (a crack releasing stored energy dissipates more than the plate puts in): the factor
//   falls by about a factor 2 every `doubling_time` / 4, to 1 at the least;
// - comfortably quasi-static: kinetic energy below half that bound and no burst: the factor
//   about doubles every `doubling_time`, to `max_factor` at the most;
// - in between it holds.
// A smooth change (a doubling over about one period of the specimen's first mode) excites no
// vibration of its own; a falling factor reacts four times faster than a rising one.
#include <cstdint>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/archive.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/solver/energy.hpp"

namespace rcdem {

class LoadingRate {
 public:
  static constexpr std::int64_t kCheckSteps = 20;

  LoadingRate() = default;
  explicit LoadingRate(const LoadingRateSettings& s) : s_(s) {}

  bool adaptive() const { return s_.adaptive; }
  // The factor on every prescribed speed for the next step.
  Real factor() const { return st_.factor; }
  // After step `step` (of length dt) with the ledger as it stands.
  void update(std::int64_t step, Real dt, const Energy& ledger);

  // The checkpoint's "loading_rate" (core/archive.hpp): the controller's memory; 1, 0, 0 when off.
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& l) {
    ar.record("loading_rate", named("factor", "1", l.st_.factor), named("work", "J", l.st_.work),
              named("damage", "J", l.st_.damage));
  }

 private:
  struct State {
    Real factor = 1.0;
    Real work = 0.0, damage = 0.0;  // the ledger's at the last check
  };
  LoadingRateSettings s_;
  State st_;
};

}  // namespace rcdem
