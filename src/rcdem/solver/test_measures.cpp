#include "rcdem/solver/test_measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rcdem/core/error.hpp"

namespace rcdem {

Gauge::MaterialPoint Gauge::material_point(const Vec3& p, Real radius, const Simulation& sim) {
  const Bodies& b = sim.bodies();
  MaterialPoint m{p, {}};
  Index nearest = 0;
  Real best = std::numeric_limits<Real>::infinity();
  for (Index i = 0; i < sim.concrete_count(); ++i) {
    const Real d = (b.position0[i] - p).norm();
    if (d < best) {
      best = d;
      nearest = i;
    }
    if (radius > 0.0 && d <= radius) m.particles.push_back(i);
  }
  if (m.particles.empty()) m.particles.push_back(nearest);
  return m;
}

Vec3 Gauge::displacement(const MaterialPoint& m, const Bodies& b) {
  Vec3 sum = Vec3::Zero();
  for (const Index i : m.particles)
    sum += b.position[i] + b.orientation[i] * (m.point - b.position0[i]) - m.point;
  return sum / static_cast<Real>(m.particles.size());
}

Gauge::Gauge(const GaugeSettings& s, const Simulation& sim)
    : name_(s.name),
      kind_(s.kind),
      a_(material_point(s.point, s.radius, sim)),
      b_(s.kind == GaugeKind::Opening ? material_point(s.to, s.radius, sim) : a_) {
  const int d = s.direction();
  direction_ = d == GaugeSettings::kAlong ? Vec3((s.to - s.point).normalized())
                                          : Vec3(Vec3::Unit(d));
  for (const auto& name : s.relative_to) relative_to_.push_back(sim.find_plate(name));
}

Real Gauge::value(const Simulation& sim) const {
  const Bodies& b = sim.bodies();
  if (kind_ == GaugeKind::Opening) return (displacement(b_, b) - displacement(a_, b)).dot(direction_);
  Real u = displacement(a_, b).dot(direction_);
  if (relative_to_.empty()) return u;
  Real reference = 0.0;
  for (const Plate* p : relative_to_) reference += p->displacement * direction_[p->axis];
  return u - reference / static_cast<Real>(relative_to_.size());
}

TestMeasures::TestMeasures(const Simulation& sim, const Scenario& sc)
    : sim_(sim), bar_(sim.find_pulled_bar(sc.control_bar)) {
  for (const auto& name : sc.load_plates())
    if (const Plate* p = sim.find_plate(name)) plates_.push_back(p);
  for (const auto& g : sc.gauges) {
    if (g.name == sc.displacement_gauge) displacement_gauge_ = static_cast<int>(gauges_.size());
    gauges_.emplace_back(g, sim);
  }
}

Real TestMeasures::load() const {
  if (bar_) return bar_->load();
  if (plates_.size() == 1) return plates_[0]->load();  // as read, signed zero included
  Real sum = 0.0;
  for (const Plate* p : plates_) sum += p->load();
  return sum;
}

Real TestMeasures::control_displacement() const {
  if (bar_) return bar_->displacement;
  if (plates_.empty()) return 0.0;
  if (plates_.size() == 1) return plates_[0]->displacement;
  Real sum = 0.0;
  for (const Plate* p : plates_) sum += p->displacement;
  return sum / static_cast<Real>(plates_.size());
}

Real TestMeasures::displacement() const {
  return displacement_gauge_ >= 0 ? gauges_[static_cast<std::size_t>(displacement_gauge_)].value(sim_)
                                  : control_displacement();
}

Real TestMeasures::speed() const {
  Real v = bar_ ? bar_->speed : 0.0;
  for (const Plate* p : plates_) v = std::max(v, std::abs(p->velocity));
  return v;
}

Real TestMeasures::ramp() const {
  Real t = bar_ ? bar_->ramp_time : 0.0;
  for (const Plate* p : plates_) t = std::max(t, p->ramp_time);
  return t;
}

}  // namespace rcdem
