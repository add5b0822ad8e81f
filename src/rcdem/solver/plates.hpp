#pragma once
// Rigid plates (platens, supports, loading plates; SPEC 6): axis-aligned rectangles on a face of
// the specimen, moved under displacement control. A plate acts on the particles whose Voronoi
// cells have a face on its side of the specimen: one contact point at that face's centroid, with
// the stiffness a particle-particle contact of the same area would have with the particle's
// mirror image, k_n = E_bar A / (2 h0) and k_s = alpha k_n (h0: centre-to-face distance at t = 0).
// Whether the point lies on the plate is checked every step, so contacts start and end as the
// specimen moves.
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/config/specimen_geometry.hpp"
#include "rcdem/contact/laws/local_point_state.hpp"
#include "rcdem/core/archive.hpp"
#include "rcdem/core/types.hpp"
#include "rcdem/solver/loading_program.hpp"
#include "rcdem/solver/step_part.hpp"
#include "rcdem/state/bodies.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

struct Plate {
  std::string name;
  int axis = 2;
  int side = -1;                    // -1: on the low face of the axis (normal +axis), +1: high face
  Vec3 normal;                      // unit, into the specimen
  Real face_coordinate = 0.0;       // the face's coordinate along the axis at t = 0
  Real u_min, u_max, v_min, v_max;  // rectangle in the other two axes (ascending order)
  Real velocity = 0.0;              // along +axis (a program's plate: 0)
  Real ramp_time = 0.0;
  // How it moves: `velocity` after the ramp, or its program (solver/loading_program.hpp).
  LoadingProgram motion{0.0, 0.0};
  // The way along the axis its load grows (Plate::load): its velocity's sign, its program's first
  // move's (into the specimen when that is a load), or `side` for a plate that stays still.
  Real direction = 1.0;
  bool glued = false;
  Real friction = 0.0;

  Real displacement = 0.0;    // along +axis since t = 0
  Vec3 force = Vec3::Zero();  // exerted on the plate by the specimen
  Real work = 0.0;            // done by the plate on the specimen
  Index contacts_active = 0;

  // From now on a constant velocity (a program's plate leaves its program), reached over the ramp
  // time from t = 0 as at the start: once that time has passed, the change is immediate (a held
  // plate, 0, stops at once). The load keeps the sign the test began with (`direction`), so that
  // unloading reads as a falling load, not a negative one.
  void set_velocity(Real v) {
    velocity = v;
    motion = LoadingProgram(v, ramp_time);
  }
  // The reaction along the axis, signed so that it is positive when it resists the plate's
  // motion in `direction`.
  Real load() const { return -direction * force[axis]; }
};

struct PlateContacts {
  std::vector<int> plate;
  std::vector<Index> particle;
  std::vector<Vec3> point0;  // the face centroid at t = 0
  std::vector<LocalPointConstants> constants;
  std::vector<LocalPointState> state;
  std::vector<Vec3> force;   // on the particle, this step
  std::vector<Vec3> torque;  // on the particle, about its centre
  std::vector<Real> strain_energy, dissipated_friction;
  std::vector<std::uint8_t> active;
  // Unglued plates: the opening at which the contact last became active (<= 0). A point that
  // slides onto the rectangle already below the plate's plane (it passed the plate's edge, not
  // its face) starts from zero force there instead of from k_n times that penetration: an impulse
  // that created strain energy from nothing (a 3 kN jump of a support's reaction in one step on
  // the quick AN3 beam, the balance error's largest single entry).
  std::vector<Real> entry_opening;

  Index size() const { return static_cast<Index>(plate.size()); }
};

// The plates with their contacts as a part of the step (solver/step_part.hpp): the contacts in
// small tasks, the reactions summed in a fixed order, and after each move the plates' work and
// their next move under displacement control.
struct PlateSet final : StepPart {
  static constexpr Index kTaskSize = 256;  // contacts per task

  std::vector<Plate> plates;
  PlateContacts contacts;
  std::vector<Real> force_prev, displacement_prev;  // per plate, at the last step

  PlateSet(const std::vector<PlateSettings>& settings, const SpecimenGeometry& geometry,
           const BoundaryFaces& faces, const Bodies& bodies, const ContactParameters& params);
  const Plate* find(const std::string& name) const;
  bool has_program() const;

  Index task_count() const override;
  void run_task(Index task, const StepContext& ctx) override;
  void finish_evaluation() override;
  void scatter(Bodies& bodies) const override;
  void drive(const Bodies& bodies, const StepClock& clock, Energy& ledger) override;
  void add_dissipation(StepDissipation& d) const override;
  void add_strain_energy(Real& sum) const override;
  void visit_springs(SpringVisitor& v, const Bodies& bodies) const override;

  // The checkpoint's "plates" and "plate_contacts" (core/archive.hpp): what a step changes.
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& s) {
    ar.table("plates", s.plates.size(), column("displacement", "m", s.plates, &Plate::displacement),
             column("force", "N", s.plates, &Plate::force),
             column("work", "J", s.plates, &Plate::work),
             column("contacts_active", "-", s.plates, &Plate::contacts_active),
             column("force_prev", "N", s.force_prev),
             column("displacement_prev", "m", s.displacement_prev));
    // Only where a plate has a program, so that the checkpoints of the runs without one keep
    // their format.
    if (s.has_program())
      ar.table(
          "plate_programs", s.plates.size(),
          column_of(
              "program", "", [&](std::size_t i) -> auto& { return s.plates[i].motion.state(); }));
    auto& pc = s.contacts;
    ar.table("plate_contacts", pc.state.size(), column("point", "", pc.state),
             column("force", "N", pc.force), column("torque", "N*m", pc.torque),
             column("strain_energy", "J", pc.strain_energy),
             column("dissipated_friction", "J", pc.dissipated_friction),
             column("active", "-", pc.active), column("entry_opening", "m", pc.entry_opening));
  }
};

std::vector<Plate> make_plates(const std::vector<PlateSettings>& settings,
                               const SpecimenGeometry& geometry);

// One contact for every boundary face on a plate's face (inside the rectangle or not: that is
// decided every step). Fails if a plate touches no particle.
PlateContacts make_plate_contacts(const std::vector<Plate>& plates, const BoundaryFaces& faces,
                                  const Bodies& bodies, const ContactParameters& params);

// Contact forces between plates and particles (SPEC 6), and each plate's reaction.
void evaluate_plate_contacts(std::vector<Plate>& plates, PlateContacts& pc, const Bodies& bodies);
// The same in two parts, for a caller that spreads the contacts over its own tasks: contact k
// (writes only its own entries), then the plates' reactions and active counts, in a fixed order.
void evaluate_plate_contact(const std::vector<Plate>& plates, PlateContacts& pc,
                            const Bodies& bodies, Index k);
void sum_plate_reactions(std::vector<Plate>& plates, const PlateContacts& pc);

}  // namespace rcdem
