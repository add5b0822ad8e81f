#pragma once
// How a plate or a pulled bar moves (issue 41, item 2; docs/model.md 13): a program of segments
// (config/scenario.hpp, SegmentSettings), or a constant velocity. Every change of velocity, at the
// start and between segments, follows one cosine ramp over the part's ramp time; a segment ends at
// the first step its goal is met or passed (a displacement or load reached, its duration over;
// a force segment's duration counts from the first step its load is within its tolerance of the
// target), and the next starts there. After the last segment the part stands still.
//
// Velocities, displacements and loads are the part's own: a plate's along its axis and its load
// (Plate::load), a pulled bar's along its pull and its pull-out force. `direction` is the way the
// load grows (+1 or -1 along the axis): a 'load' segment moves that way to raise the load and
// back to lower it, and the force servo turns the load's error into a velocity that way.
#include <concepts>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/archive.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/solver/step_part.hpp"

namespace rcdem {

class LoadingProgram {
 public:
  // A constant velocity reached over the ramp time from rest at t = 0.
  LoadingProgram(Real velocity, Real ramp_time);
  // The segments given (cycles expanded into their moves), from rest at t = 0.
  LoadingProgram(const std::vector<SegmentSettings>& segments, Real ramp_time, Real direction);

  // The velocity over the move from clock.time to clock.time + dt (sampled at its middle), the
  // part at `displacement` carrying `load` now; first ends the segments whose goal is met.
  // Fails naming `part` where the force servo cannot estimate the specimen's stiffness.
  Real velocity(const StepClock& clock, Real displacement, Real load, const std::string& part);

  bool explicit_program() const { return !constant_; }
  bool finished() const { return st_.segment >= static_cast<std::int64_t>(segments_.size()); }
  std::int64_t segment() const { return st_.segment; }
  // The way the load grows for the segments given: the sign of the first move that has one.
  static Real first_direction(const std::vector<SegmentSettings>& segments, Real otherwise);

  // Where the program is: what a resumed run needs to continue it bitwise.
  struct State {
    std::int64_t segment = 0;
    Real start_time = 0.0, start_displacement = 0.0, start_load = 0.0;
    Real ramp_from = 0.0;  // the velocity the ramp starts from
    Real last = 0.0;       // the last velocity returned
    Real stiffness = 0.0;  // a force segment's
    Real reached = -1.0;   // a force segment's: when the load first came within its tolerance
    std::int64_t started = 0;
  };
  State& state() { return st_; }
  const State& state() const { return st_; }

 private:
  struct Segment {
    SegmentKind kind;
    Real velocity, duration, target, speed, response_time, stiffness, tolerance;
  };
  bool goal_met(const Segment& s, Real t, Real displacement, Real load) const;
  Real nominal(const Segment& s, Real displacement, Real load) const;
  void start_segment(Real t, Real displacement, Real load, const std::string& part);

  std::vector<Segment> segments_;
  Real ramp_time_ = 0.0;
  Real direction_ = 1.0;
  bool constant_ = false;
  State st_;
};

// The state's fields in the checkpoint's order (core/archive.hpp).
template <class Record, class S>
requires std::same_as<std::remove_const_t<S>, LoadingProgram::State>
void archive_fields(Record& r, S& s) {
  r.put(named("segment", "-", s.segment));
  r.put(named("start_time", "s", s.start_time));
  r.put(named("start_displacement", "m", s.start_displacement));
  r.put(named("start_load", "N", s.start_load));
  r.put(named("ramp_from", "m/s", s.ramp_from));
  r.put(named("last", "m/s", s.last));
  r.put(named("stiffness", "N/m", s.stiffness));
  r.put(named("reached", "s", s.reached));
  r.put(named("started", "-", s.started));
}

}  // namespace rcdem
