#include "rcdem/solver/pulled_bars.hpp"

#include <cmath>

#include "rcdem/solver/energy.hpp"

namespace rcdem {

PulledBars::PulledBars(const Scenario& sc, const Specimen& specimen, PrescribedMotion& motion) {
  Index body = specimen.concrete();
  for (std::size_t k = 0; k < specimen.bars.size(); ++k) {
    const BarSettings& bs = sc.bars[k];
    if (bs.pulled()) {
      PulledBar pb;
      pb.name = bs.name;
      pb.body = body;
      // Along its first chord, out of the specimen (a straight bar: end -> start).
      const std::vector<Vec3> axis = bs.centreline();
      pb.direction = (axis[0] - axis[1]).normalized();
      pb.speed = bs.pull_velocity;
      pb.ramp_time = bs.pull_ramp_time;
      pb.motion = bs.program.empty() ? LoadingProgram(bs.pull_velocity, bs.pull_ramp_time)
                                     : LoadingProgram(bs.program, bs.pull_ramp_time, 1.0);
      slot.push_back(motion.claim(body));
      bars.push_back(pb);
    }
    body += static_cast<Index>(specimen.bars[k].cylinders.size());
  }
  force_prev.assign(bars.size(), 0.0);
}

void PulledBars::prescribe(PrescribedMotion& motion, const StepClock& clock) {
  for (std::size_t k = 0; k < bars.size(); ++k)
    motion.velocity[slot[k]] =
        clock.rate *
        bars[k].motion.velocity(clock, bars[k].displacement, bars[k].load(), bars[k].name) *
        bars[k].direction;
}

void PulledBars::drive(const Bodies& bodies, const StepClock& clock, Energy& ledger) {
  // The driver's work over the last move (trapezoidal in its force), then this move's length.
  for (std::size_t k = 0; k < bars.size(); ++k) {
    PulledBar& pb = bars[k];
    pb.force = bodies.force[pb.body];
    const Real f_driver = pb.load();
    const Real work = 0.5 * (force_prev[k] + f_driver) * pb.last_step;
    pb.work += work;
    ledger.external_work += work;
    force_prev[k] = f_driver;
    pb.last_step = bodies.velocity[pb.body].dot(pb.direction) * clock.dt;
    pb.displacement += pb.last_step;
  }
}

const PulledBar* PulledBars::find(const std::string& name) const {
  for (const auto& b : bars)
    if (b.name == name) return &b;
  return nullptr;
}

}  // namespace rcdem
