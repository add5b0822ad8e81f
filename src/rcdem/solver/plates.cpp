#include "rcdem/solver/plates.hpp"

#include <algorithm>
#include <cmath>

#include "rcdem/core/error.hpp"
#include "rcdem/core/parallel.hpp"
#include "rcdem/solver/energy.hpp"

namespace rcdem {

std::vector<Plate> make_plates(const std::vector<PlateSettings>& settings,
                               const SpecimenGeometry& g) {
  std::vector<Plate> plates;
  for (const auto& s : settings) {
    Plate p;
    p.name = s.name;
    p.axis = s.axis;
    p.side = s.side;
    p.normal = Vec3::Zero();
    p.normal[s.axis] = -s.side;
    p.face_coordinate = s.side < 0 ? g.lo[s.axis] : g.hi[s.axis];
    const auto [u, v] = face_axes(s.axis);
    if (s.extent.empty()) {
      p.u_min = g.lo[u];
      p.u_max = g.hi[u];
      p.v_min = g.lo[v];
      p.v_max = g.hi[v];
    } else {
      p.u_min = s.extent[0];
      p.u_max = s.extent[1];
      p.v_min = s.extent[2];
      p.v_max = s.extent[3];
    }
    p.velocity = s.velocity;
    p.ramp_time = s.ramp_time;
    if (s.program.empty()) {
      p.motion = LoadingProgram(s.velocity, s.ramp_time);
      p.direction = s.velocity > 0.0 ? 1.0 : s.velocity < 0.0 ? -1.0 : s.side;
    } else {
      p.direction = LoadingProgram::first_direction(s.program, -s.side);
      p.motion = LoadingProgram(s.program, s.ramp_time, p.direction);
    }
    p.glued = s.glued;
    p.friction = s.friction;
    plates.push_back(p);
  }
  return plates;
}

PlateContacts make_plate_contacts(const std::vector<Plate>& plates, const BoundaryFaces& faces,
                                  const Bodies& bodies, const ContactParameters& params) {
  PlateContacts pc;
  for (std::size_t p = 0; p < plates.size(); ++p) {
    const Plate& plate = plates[p];
    const int face = 2 * plate.axis + (plate.side > 0 ? 1 : 0);
    const auto [u, v] = face_axes(plate.axis);
    Index touching = 0;
    for (Index k = 0; k < faces.size(); ++k) {
      if (faces.face[k] != face) continue;
      const Index i = faces.particle[k];
      const Vec3& c = faces.centroid[k];
      // Only faces within reach of the plate become contacts: a particle may slide onto the
      // rectangle during the run, but not from farther than a few of its radii. The others would
      // be evaluated every step for nothing (supports cover 6% of a beam's bottom face).
      const Real reach = 4.0 * bodies.radius[i];
      if (c[u] < plate.u_min - reach || c[u] > plate.u_max + reach || c[v] < plate.v_min - reach ||
          c[v] > plate.v_max + reach)
        continue;
      const Real h0 = std::abs(bodies.position0[i][plate.axis] - plate.face_coordinate);
      const Real kn = params.E_bar * faces.area[k] / (2.0 * h0);
      pc.plate.push_back(static_cast<int>(p));
      pc.particle.push_back(i);
      pc.point0.push_back(c);
      pc.constants.push_back({kn, params.alpha * kn, 0.0, 0.0});
      touching += (c[u] >= plate.u_min && c[u] <= plate.u_max && c[v] >= plate.v_min &&
                   c[v] <= plate.v_max);
    }
    if (touching == 0)
      fail(
          "plate '{}' touches no particle: its rectangle [{}, {}] x [{}, {}] m misses the "
          "specimen's face",
          plate.name, plate.u_min, plate.u_max, plate.v_min, plate.v_max);
  }
  const auto n = static_cast<std::size_t>(pc.size());
  pc.state.assign(n, LocalPointState{});
  pc.force.assign(n, Vec3::Zero());
  pc.torque.assign(n, Vec3::Zero());
  pc.strain_energy.assign(n, 0.0);
  pc.dissipated_friction.assign(n, 0.0);
  pc.active.assign(n, 0);
  pc.entry_opening.assign(n, 0.0);
  return pc;
}

void evaluate_plate_contact(const std::vector<Plate>& plates, PlateContacts& pc, const Bodies& b,
                            Index k) {
  const Plate& plate = plates[static_cast<std::size_t>(pc.plate[k])];
  const Index i = pc.particle[k];
  const Vec3 n = plate.normal;
  // The particle's material point that lay on the face at t = 0, against the plate's.
  const Vec3 pp = b.position[i] + b.orientation[i] * (pc.point0[k] - b.position0[i]);
  Vec3 plate_point = pc.point0[k];
  plate_point[plate.axis] += plate.displacement;
  const Vec3 u = pp - plate_point;
  const Real un = u.dot(n);  // opening positive: the particle moving off the plate
  const Vec3 us = u - un * n;
  const auto [ua, va] = face_axes(plate.axis);
  const bool on_plate = pp[ua] >= plate.u_min && pp[ua] <= plate.u_max && pp[va] >= plate.v_min &&
                        pp[va] <= plate.v_max;
  LocalPointState& s = pc.state[k];
  const LocalPointConstants& c = pc.constants[k];
  const bool was_active = pc.active[k] != 0;
  // An unglued contact that reaches the rectangle from beside it, already below the plate's
  // plane (its last opening, kept while it was inactive, was negative too), measures its
  // opening from where it entered; one that meets the plate face-on, from the plane.
  if (!plate.glued && !was_active && on_plate)
    pc.entry_opening[k] = (s.un < 0.0 && un < 0.0) ? un : 0.0;
  const Real opening = plate.glued ? un : un - pc.entry_opening[k];
  Real friction_loss = 0.0;
  if (!on_plate || (!plate.glued && opening > 0.0)) {
    // Separated (or off the rectangle): the contact forgets its history, and the energy its
    // springs held leaves the model; the ledger books it as lost, not as vanished.
    if (was_active) friction_loss = 0.5 * s.fn * s.fn / c.kn + 0.5 * s.fs.squaredNorm() / c.ks;
    s = LocalPointState{};
    s.un = un;
    s.us = us;
    pc.active[k] = 0;
    pc.entry_opening[k] = 0.0;
  } else if (plate.glued) {
    s.fn = c.kn * un;
    s.fs = -c.ks * us;
    s.un = un;
    s.us = us;
    pc.active[k] = 1;
  } else {
    // Unilateral, Coulomb friction: the shear spring is incremental so that it can slide.
    const Vec3 dus = was_active ? Vec3(us - s.us) : Vec3::Zero();
    const Vec3 fs_old = s.fs;
    s.fn = c.kn * opening;  // compression: negative
    Vec3 fs = s.fs - c.ks * dus;
    const Real cap = plate.friction * (-s.fn);
    const Real len = fs.norm();
    if (len > cap) fs *= (len > 0.0 ? cap / len : 0.0);
    // Work of the slip on the spring minus its change of energy: the friction loss.
    const Real work = -0.5 * (fs_old + fs).dot(dus);
    friction_loss = work - (fs.squaredNorm() - fs_old.squaredNorm()) / (2.0 * c.ks);
    s.fs = fs;
    s.un = un;
    s.us = us;
    pc.active[k] = 1;
  }
  const Vec3 f = -s.fn * n + s.fs;
  pc.force[k] = f;
  pc.torque[k] = (pp - b.position[i]).cross(f);
  pc.strain_energy[k] =
      pc.active[k] ? 0.5 * s.fn * s.fn / c.kn + 0.5 * s.fs.squaredNorm() / c.ks : 0.0;
  pc.dissipated_friction[k] = friction_loss;
}

void evaluate_plate_contacts(std::vector<Plate>& plates, PlateContacts& pc, const Bodies& b) {
  parallel_for(pc.size(), [&](Index k) { evaluate_plate_contact(plates, pc, b, k); });
  sum_plate_reactions(plates, pc);
}

void sum_plate_reactions(std::vector<Plate>& plates, const PlateContacts& pc) {
  // The reactions, summed in a fixed order.
  for (auto& p : plates) {
    p.force = Vec3::Zero();
    p.contacts_active = 0;
  }
  for (Index k = 0; k < pc.size(); ++k) {
    Plate& p = plates[static_cast<std::size_t>(pc.plate[k])];
    p.force -= pc.force[k];
    p.contacts_active += pc.active[k];
  }
}

PlateSet::PlateSet(const std::vector<PlateSettings>& settings, const SpecimenGeometry& geometry,
                   const BoundaryFaces& faces, const Bodies& bodies,
                   const ContactParameters& params)
    : plates(make_plates(settings, geometry)),
      contacts(make_plate_contacts(plates, faces, bodies, params)),
      force_prev(plates.size(), 0.0),
      displacement_prev(plates.size(), 0.0) {}

Index PlateSet::task_count() const { return (contacts.size() + kTaskSize - 1) / kTaskSize; }

void PlateSet::run_task(Index task, const StepContext& ctx) {
  const Index end = std::min(contacts.size(), (task + 1) * kTaskSize);
  for (Index k = task * kTaskSize; k < end; ++k)
    evaluate_plate_contact(plates, contacts, ctx.bodies, k);
}

void PlateSet::finish_evaluation() { sum_plate_reactions(plates, contacts); }

void PlateSet::scatter(Bodies& bodies) const {
  for (Index j = 0; j < contacts.size(); ++j) {
    const Index i = contacts.particle[j];
    bodies.force[i] += contacts.force[j];
    bodies.torque[i] += contacts.torque[j];
  }
}

void PlateSet::drive(const Bodies&, const StepClock& clock, Energy& ledger) {
  // The work done over the last move (trapezoidal in the force), then the next move.
  for (std::size_t p = 0; p < plates.size(); ++p) {
    Plate& plate = plates[p];
    const Real f_on_specimen = -plate.force[plate.axis];
    const Real work =
        0.5 * (force_prev[p] + f_on_specimen) * (plate.displacement - displacement_prev[p]);
    plate.work += work;
    ledger.external_work += work;
    force_prev[p] = f_on_specimen;
    displacement_prev[p] = plate.displacement;
    plate.displacement +=
        clock.rate * plate.motion.velocity(clock, plate.displacement, plate.load(), plate.name) *
        clock.dt;
  }
}

void PlateSet::add_dissipation(StepDissipation& d) const {
  for (Index j = 0; j < contacts.size(); ++j) d.friction += contacts.dissipated_friction[j];
}

void PlateSet::add_strain_energy(Real& sum) const {
  for (Index j = 0; j < contacts.size(); ++j) sum += contacts.strain_energy[j];
}

void PlateSet::visit_springs(SpringVisitor& v, const Bodies& bodies) const {
  // Every plate contact, closed or not: the stiffest the plates can make the assembly.
  for (Index j = 0; j < contacts.size(); ++j) {
    const Index i = contacts.particle[j];
    const LocalPointConstants& k = contacts.constants[j];
    const Vec3 arm = contacts.point0[j] - bodies.position0[i];
    v.spring(-1, i, arm, arm, plates[contacts.plate[j]].normal, k.kn, k.ks);
  }
}

bool PlateSet::has_program() const {
  return std::any_of(plates.begin(), plates.end(),
                     [](const Plate& p) { return p.motion.explicit_program(); });
}

const Plate* PlateSet::find(const std::string& name) const {
  for (const auto& p : plates)
    if (p.name == name) return &p;
  return nullptr;
}

}  // namespace rcdem
