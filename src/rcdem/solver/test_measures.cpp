#include "rcdem/solver/test_measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "rcdem/config/scenario_checks.hpp"
#include "rcdem/core/error.hpp"

namespace rcdem {

Gauge::MaterialPoint Gauge::material_point(const Vec3& p, Real radius, const Simulation& sim,
                                           const std::string& gauge) {
  const Bodies& b = sim.bodies();
  MaterialPoint m{p, {}, {}};
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
  if (radius <= 0.0) {
    m.particles.push_back(nearest);
    return m;
  }
  // u(p) = mean u + G (p - c), G the least-squares gradient over the offsets d_i from the
  // centroid c: the weights 1/n + d_i^T M^-1 (p - c), M = sum d_i d_i^T.
  const auto n = static_cast<Real>(m.particles.size());
  Vec3 c = Vec3::Zero();
  for (const Index i : m.particles) c += b.position0[i];
  c /= n;
  Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
  for (const Index i : m.particles)
    moment += (b.position0[i] - c) * (b.position0[i] - c).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(moment);
  // The particles must span the three directions: the smallest principal spread at least a
  // hundredth of the largest.
  if (m.particles.size() < 4 || !(eig.eigenvalues()(0) > 1e-4 * eig.eigenvalues()(2)))
    fail(
        "{}: the {} particle(s) within radius {} m of ({}, {}, {}) do not span three "
        "directions; expected a larger radius (about two particle diameters) or radius = 0",
        gauge, m.particles.size(), radius, p.x(), p.y(), p.z());
  const Vec3 lever = moment.inverse() * (p - c);
  for (const Index i : m.particles) m.weight.push_back(1.0 / n + (b.position0[i] - c).dot(lever));
  return m;
}

Vec3 Gauge::displacement(const MaterialPoint& m, const Bodies& b) {
  if (m.weight.empty()) {
    const Index i = m.particles[0];
    return b.position[i] + b.orientation[i] * (m.point - b.position0[i]) - m.point;
  }
  Vec3 u = Vec3::Zero();
  for (std::size_t k = 0; k < m.particles.size(); ++k) {
    const Index i = m.particles[k];
    u += m.weight[k] * (b.position[i] - b.position0[i]);
  }
  return u;
}

Gauge::Gauge(const GaugeSettings& s, const Simulation& sim, const std::string& where)
    : name_(s.name),
      kind_(s.kind),
      a_(material_point(s.point, s.radius, sim, where)),
      b_(s.kind == GaugeKind::Opening ? material_point(s.to, s.radius, sim, where) : a_) {
  const int d = s.direction();
  direction_ =
      d == GaugeSettings::kAlong ? Vec3((s.to - s.point).normalized()) : Vec3(Vec3::Unit(d));
  for (const auto& name : s.relative_to) relative_to_.push_back(sim.find_plate(name));
}

std::vector<Index> Gauge::particles() const {
  std::vector<Index> out(a_.particles);
  out.insert(out.end(), b_.particles.begin(), b_.particles.end());
  return out;
}

Real Gauge::value(const Simulation& sim) const {
  const Bodies& b = sim.bodies_as_stepped();
  if (kind_ == GaugeKind::Opening)
    return (displacement(b_, b) - displacement(a_, b)).dot(direction_);
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
    gauges_.emplace_back(g, sim,
                         config::key_location(sc, "gauges." + g.name + ".radius") +
                             ": key 'gauges." + g.name + ".radius'");
  }
}

std::vector<Index> TestMeasures::gauge_particles() const {
  std::vector<Index> out;
  for (const Gauge& g : gauges_) {
    const std::vector<Index> p = g.particles();
    out.insert(out.end(), p.begin(), p.end());
  }
  return out;
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
  return displacement_gauge_ >= 0
             ? gauges_[static_cast<std::size_t>(displacement_gauge_)].value(sim_)
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
