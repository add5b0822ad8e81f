#include "rcdem/solver/loading_program.hpp"

#include <algorithm>
#include <cmath>

#include "rcdem/core/error.hpp"

namespace rcdem {

namespace {
// The cosine ramp from `from` to `to` over `duration` from `start`: smooth in velocity, so that
// no change of speed sends a shock through the specimen.
Real ramp(Real from, Real to, Real start, Real duration, Real t) {
  if (duration <= 0.0 || t - start >= duration) return to;
  return from + (to - from) * 0.5 * (1.0 - std::cos(kPi * (t - start) / duration));
}

Real sign(Real x) { return x > 0.0 ? 1.0 : x < 0.0 ? -1.0 : 0.0; }
}  // namespace

LoadingProgram::LoadingProgram(Real velocity, Real ramp_time)
    : segments_{{SegmentKind::Velocity, velocity, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0}},
      ramp_time_(ramp_time),
      constant_(true) {}

LoadingProgram::LoadingProgram(const std::vector<SegmentSettings>& segments, Real ramp_time,
                               Real direction)
    : ramp_time_(ramp_time), direction_(direction) {
  for (const SegmentSettings& g : segments) {
    if (g.kind != SegmentKind::Cycles) {
      segments_.push_back({g.kind, g.velocity, g.duration, g.target, g.speed, g.response_time,
                           g.stiffness, g.tolerance});
      continue;
    }
    for (std::int64_t k = 0; k < g.count; ++k) {
      const Real peak = g.amplitude + static_cast<Real>(k) * g.amplitude_step;
      segments_.push_back({SegmentKind::Displacement, 0.0, 0.0, peak, g.speed, 0.0, 0.0, 0.0});
      segments_.push_back({SegmentKind::Load, 0.0, 0.0, g.unload_to, g.speed, 0.0, 0.0, 0.0});
    }
  }
}

Real LoadingProgram::first_direction(const std::vector<SegmentSettings>& segments,
                                     Real otherwise) {
  for (const SegmentSettings& g : segments) {
    const Real s = g.kind == SegmentKind::Velocity       ? sign(g.velocity)
                   : g.kind == SegmentKind::Displacement ? sign(g.target)
                   : g.kind == SegmentKind::Cycles       ? sign(g.amplitude)
                                                         : 0.0;
    if (s != 0.0) return s;
  }
  return otherwise;
}

bool LoadingProgram::goal_met(const Segment& s, Real t, Real displacement, Real load) const {
  switch (s.kind) {
    case SegmentKind::Velocity:
      return s.duration > 0.0 && t - st_.start_time >= s.duration;
    case SegmentKind::Hold:
      return t - st_.start_time >= s.duration;
    case SegmentKind::Force:
      return st_.reached >= 0.0 && t - st_.reached >= s.duration;
    case SegmentKind::Displacement:
      // Reached or passed, from the side it started on (there already: done).
      return (displacement - s.target) * sign(s.target - st_.start_displacement) >= 0.0;
    case SegmentKind::Load:
      return (load - s.target) * sign(s.target - st_.start_load) >= 0.0;
    case SegmentKind::Cycles:
      break;
  }
  return true;
}

Real LoadingProgram::nominal(const Segment& s, Real displacement, Real load) const {
  switch (s.kind) {
    case SegmentKind::Velocity:
      return s.velocity;
    case SegmentKind::Hold:
      return 0.0;
    case SegmentKind::Displacement:
      return s.speed * sign(s.target - displacement);
    case SegmentKind::Load:
      return s.speed * direction_ * sign(s.target - st_.start_load);
    case SegmentKind::Force: {
      // First order: the load approaches the target with the time constant response_time if the
      // specimen's stiffness is the one assumed (docs/model.md 13).
      const Real v = direction_ * (s.target - load) / (st_.stiffness * s.response_time);
      return std::clamp(v, -s.speed, s.speed);
    }
    case SegmentKind::Cycles:
      break;
  }
  return 0.0;
}

void LoadingProgram::start_segment(Real t, Real displacement, Real load, const std::string& part) {
  ++st_.segment;
  st_.start_time = t;
  st_.start_displacement = displacement;
  st_.start_load = load;
  st_.ramp_from = st_.last;
  st_.reached = -1.0;
  if (finished()) return;
  const Segment& s = segments_[static_cast<std::size_t>(st_.segment)];
  if (s.kind != SegmentKind::Force) return;
  st_.stiffness = s.stiffness > 0.0 ? s.stiffness : load / (direction_ * displacement);
  if (!(st_.stiffness > 0.0 && std::isfinite(st_.stiffness)))
    fail(
        "{}: its program's force segment starts at {:.4g} N and {:.4g} m, from which no "
        "stiffness can be estimated: load the specimen first, or set the segment's stiffness",
        part, load, displacement);
}

Real LoadingProgram::velocity(const StepClock& clock, Real displacement, Real load,
                              const std::string& part) {
  if (constant_) return ramp(0.0, segments_[0].velocity, 0.0, ramp_time_, clock.mid());
  if (!st_.started) {
    // The first segment starts at the first step: its goal is measured from this state.
    st_.started = 1;
    --st_.segment;
    start_segment(clock.time, displacement, load, part);
  }
  if (!finished()) {
    const Segment& s = segments_[static_cast<std::size_t>(st_.segment)];
    if (s.kind == SegmentKind::Force && st_.reached < 0.0 &&
        std::abs(load - s.target) <= s.tolerance * std::abs(s.target))
      st_.reached = clock.time;
  }
  while (!finished() &&
         goal_met(segments_[static_cast<std::size_t>(st_.segment)], clock.time, displacement,
                  load))
    start_segment(clock.time, displacement, load, part);
  if (finished()) {
    st_.last = ramp(st_.ramp_from, 0.0, st_.start_time, ramp_time_, clock.mid());
    return st_.last;
  }
  const Segment& s = segments_[static_cast<std::size_t>(st_.segment)];
  // The servo takes over from the previous velocity within a quarter of its response time, so
  // that the servo, not the ramp, sets how the load approaches its target (the previous motion
  // carried on over a whole ramp overshot it).
  const Real blend =
      s.kind == SegmentKind::Force ? std::min(ramp_time_, 0.25 * s.response_time) : ramp_time_;
  st_.last = ramp(st_.ramp_from, nominal(s, displacement, load), st_.start_time, blend,
                  clock.mid());
  return st_.last;
}

}  // namespace rcdem
