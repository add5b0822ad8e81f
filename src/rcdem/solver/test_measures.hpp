#pragma once
// What a test measures (issue 41): its load and displacement (loading.control_plate, the sum over
// loading.control_plates, or a pulled bar; or a gauge as the displacement), and its gauges
// (config/scenario.hpp, GaugeSettings): displacements of the material at points, relative to
// plates, and openings between two material points.
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/solver/simulation.hpp"

namespace rcdem {

// One gauge, its material points resolved to particles at t = 0.
class Gauge {
 public:
  // `where`: the key's location for errors ("FILE:LINE: key 'gauges.NAME.radius'").
  Gauge(const GaugeSettings& settings, const Simulation& sim, const std::string& where);
  const std::string& name() const { return name_; }
  // Its value now (m). Distributed, its particles must be among those rank 0 receives every step
  // (Simulation::distribute's `leader_reads`: TestMeasures::gauge_particles).
  Real value(const Simulation& sim) const;
  // The particles it reads.
  std::vector<Index> particles() const;

 private:
  // The material's displacement at a point (docs/model.md 12): with a radius, the affine field
  // fitted by least squares to the displacements of the particles' centres within it, at the
  // point (exact for any uniform strain and rigid motion), as weights on those displacements;
  // without, the nearest particle carrying the point rigidly.
  struct MaterialPoint {
    Vec3 point;
    std::vector<Index> particles;
    std::vector<Real> weight;  // empty: the one particle carries the point
  };
  static MaterialPoint material_point(const Vec3& p, Real radius, const Simulation& sim,
                                      const std::string& gauge);
  static Vec3 displacement(const MaterialPoint& m, const Bodies& b);

  std::string name_;
  GaugeKind kind_;
  Vec3 direction_;  // unit
  MaterialPoint a_, b_;
  std::vector<const Plate*> relative_to_;
};

class TestMeasures {
 public:
  TestMeasures(const Simulation& sim, const Scenario& sc);

  // The load (N): the control plates' reactions summed, or the pulled bar's force.
  Real load() const;
  // The control's displacement (m): the control plates' mean, or the pulled bar's.
  Real control_displacement() const;
  // The test's displacement: the displacement gauge's value, else the control's.
  Real displacement() const;
  // The fastest prescribed speed of the control and its ramp (for expected run lengths).
  Real speed() const;
  Real ramp() const;
  const std::vector<Gauge>& gauges() const { return gauges_; }
  // Every gauge's particles: what rank 0 of a distributed run receives every step, so that the
  // test's displacement costs no gathering of every particle.
  std::vector<Index> gauge_particles() const;
  bool several_plates() const { return plates_.size() > 1; }

 private:
  const Simulation& sim_;
  std::vector<const Plate*> plates_;
  const PulledBar* bar_ = nullptr;
  std::vector<Gauge> gauges_;
  int displacement_gauge_ = -1;
};

}  // namespace rcdem
