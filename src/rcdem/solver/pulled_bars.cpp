#include "rcdem/solver/pulled_bars.hpp"

#include <cmath>

namespace rcdem {

Real PulledBar::velocity_at(Real t) const {
  if (ramp_time <= 0.0 || t >= ramp_time) return speed;
  return speed * 0.5 * (1.0 - std::cos(kPi * t / ramp_time));
}

PulledBars PulledBars::build(const Scenario& sc, const Specimen& specimen, Index bodies) {
  PulledBars p;
  p.driven.assign(static_cast<std::size_t>(bodies), -1);
  Index body = specimen.concrete();
  for (std::size_t k = 0; k < specimen.bars.size(); ++k) {
    const BarSettings& bs = sc.bars[k];
    if (bs.pull_velocity > 0.0) {
      PulledBar pb;
      pb.name = bs.name;
      pb.body = body;
      pb.direction = (bs.start - bs.end).normalized();
      pb.speed = bs.pull_velocity;
      pb.ramp_time = bs.pull_ramp_time;
      p.driven[static_cast<std::size_t>(body)] = static_cast<std::int64_t>(p.bars.size());
      p.bars.push_back(pb);
    }
    body += static_cast<Index>(specimen.bars[k].cylinders.size());
  }
  p.force_prev.assign(p.bars.size(), 0.0);
  return p;
}

const PulledBar* PulledBars::find(const std::string& name) const {
  for (const auto& b : bars)
    if (b.name == name) return &b;
  return nullptr;
}

}  // namespace rcdem
