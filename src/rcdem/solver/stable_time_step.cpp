#include <cmath>
#include <limits>

#include "rcdem/core/error.hpp"
#include "rcdem/solver/assembled_stiffness.hpp"
#include "rcdem/solver/body_stiffness.hpp"
#include "rcdem/solver/selective_mass_scaling.hpp"
#include "rcdem/solver/simulation.hpp"

// SPEC 6's time-step estimates of a simulation from every part's springs at t = 0.
namespace rcdem {

void Simulation::visit_springs(SpringVisitor& v) const {
  for (const StepPart* p : parts_) p->visit_springs(v, bodies_);
}

namespace {
// visit_springs() into the bodies' own blocks: each spring counts on each of its bodies.
struct BlockVisitor final : SpringVisitor {
  BodyStiffness& blocks;
  const std::vector<Vec3>& centre0;
  BlockVisitor(BodyStiffness& b, const std::vector<Vec3>& c) : blocks(b), centre0(c) {}
  void network(const ContactNetwork& nw, std::vector<Vec3> normal) override {
    for (Index c = 0; c < nw.contact_count(); ++c) {
      const Index a = nw.particle_a[c], b = nw.particle_b[c];
      for (Index m = nw.point_begin[c]; m < nw.point_begin[c + 1]; ++m) {
        const LocalPointConstants& k = nw.constants[m];
        blocks.add_spring(a, normal[c], k.kn, k.ks, nw.point_position0[m] - centre0[a]);
        blocks.add_spring(b, normal[c], k.kn, k.ks, nw.point_position0[m] - centre0[b]);
      }
    }
  }
  void spring(Index a, Index b, const Vec3& arm_a, const Vec3& arm_b, const Vec3& n, Real kn,
              Real ks) override {
    if (a >= 0) blocks.add_spring(a, n, kn, ks, arm_a);
    blocks.add_spring(b, n, kn, ks, arm_b);
  }
  void rotational(Index a, Index b, const Mat3& k) override {
    blocks.add_rotational(a, k);
    blocks.add_rotational(b, k);
  }
};

// visit_springs() into the assembly's operator.
struct AssemblyVisitor final : SpringVisitor {
  AssembledStiffness& k;
  explicit AssemblyVisitor(AssembledStiffness& s) : k(s) {}
  void network(const ContactNetwork& nw, std::vector<Vec3> normal) override {
    k.add_network(nw, std::move(normal));
  }
  void spring(Index a, Index b, const Vec3& arm_a, const Vec3& arm_b, const Vec3& n, Real kn,
              Real ks) override {
    k.add_spring(a, b, arm_a, arm_b, n, kn, ks);
  }
  void rotational(Index a, Index b, const Mat3& kr) override { k.add_rotational(a, b, kr); }
};
}  // namespace

void Simulation::compute_stable_time_step(Real added_mass_limit, TimeStepEstimate estimate,
                                          const std::string& source) {
  // SPEC 6's sqrt(m / sum k) per body, with "sum k" the body's own 6x6 stiffness block
  // (solver/body_stiffness.hpp: why a block, and what the safety factor covers).
  BodyStiffness blocks(bodies_.size());
  BlockVisitor blocks_visitor(blocks, bodies_.position0);
  visit_springs(blocks_visitor);
  // Each body's own estimate, and the body and motion that set the shortest (named below).
  std::vector<Real> steps(static_cast<std::size_t>(bodies_.size()));
  Index first = 0;
  BodyStiffness::Limit l{std::numeric_limits<Real>::infinity(), false, 0};
  for (Index i = 0; i < bodies_.size(); ++i) {
    const BodyStiffness::Limit li = blocks.limit(i, bodies_.mass[i], bodies_.inertia[i],
                                                 bodies_.orientation0[i].toRotationMatrix());
    steps[static_cast<std::size_t>(i)] = li.time_step;
    if (li.time_step < l.time_step) {
      l = li;
      first = i;
    }
  }
  if (!std::isfinite(l.time_step))
    fail("the specimen has no contact: no time step can be estimated");
  const bool cylinder = first >= specimen_.concrete();
  static const char* const kWhat[] = {"rotation about body axis x", "rotation about body axis y",
                                      "rotation about body axis z"};
  static const char* const kCylinder[] = {"bending rotation", "bending rotation", "torsion"};
  time_step_.limit = fmt::format("{} {} ({})", cylinder ? "bar cylinder" : "particle", first,
                                 !l.rotation ? "translation"
                                 : cylinder  ? kCylinder[l.body_axis]
                                             : kWhat[l.body_axis]);
  // Issue 28: a step this short means a stiffness or mass far outside any material (a run would
  // need 1e12 steps per second of loading, or fill its history with inf): refused, naming why.
  if (!(l.time_step >= kMinimumTimeStep))
    fail(
        "{}: the stable time step {:.3g} s, set by {}, is below {:.0e} s: it is far too stiff "
        "for its mass; check contact.E_bar, bars.*.E, material.density and bars.*.density",
        source, l.time_step, time_step_.limit, kMinimumTimeStep);
  // Selective mass scaling (solver/selective_mass_scaling.hpp): the bodies below a common target
  // made heavier, mass and inertia alike, which lifts each one's estimate to the target exactly.
  time_step_.mass_scaling = plan_selective_mass_scaling(steps, bodies_.mass, added_mass_limit);
  for (Index i = 0; i < bodies_.size(); ++i) {
    const Real f = time_step_.mass_scaling.factor[static_cast<std::size_t>(i)];
    bodies_.mass[i] *= f;
    bodies_.inertia[i] *= f;
  }
  if (time_step_.mass_scaling.bodies_scaled > 0)
    time_step_.limit = fmt::format(
        "selective mass scaling: {} bodies up to {:.3f}x heavier, +{:.3g}% mass; unscaled {:.4g} "
        "s, set by {}",
        time_step_.mass_scaling.bodies_scaled, time_step_.mass_scaling.largest_factor,
        100.0 * time_step_.mass_scaling.added_fraction(), time_step_.mass_scaling.unscaled_step,
        time_step_.limit);
  time_step_.stable = time_step_.mass_scaling.time_step;
  if (estimate == TimeStepEstimate::Assembled) {
    // The whole assembly's critical step, with the masses as scaled (critical_time_step.hpp).
    AssembledStiffness k(bodies_);
    AssemblyVisitor assembly(k);
    visit_springs(assembly);
    time_step_.critical =
        assembled_critical_time_step(k, 1.0 / (time_step_.stable * time_step_.stable));
    time_step_.limit =
        fmt::format("{}, x 1/sqrt(1 + damping {}); per-body estimate {:.4g} s ({})",
                    time_step_.critical.how(), integrator_.damping(), time_step_.stable, time_step_.limit);
    time_step_.stable = damped_critical_time_step(time_step_.critical.time_step, integrator_.damping());
  }
}

}  // namespace rcdem
