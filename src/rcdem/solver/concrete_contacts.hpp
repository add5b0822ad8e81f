#pragma once
// The concrete network as a part of the step (solver/step_part.hpp): its law, every local point's
// history, the condensation of intact contacts, and the body -> contacts index its gather walks.
// Its evaluation reads the step's kinematics; a condensed contact's catch-up reads the last
// evaluation's (contact_loop.hpp, evaluate_contacts).
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/contact/contact_loop.hpp"
#include "rcdem/contact/contact_state.hpp"
#include "rcdem/contact/elastic_condensation.hpp"
#include "rcdem/contact/laws/law_registry.hpp"
#include "rcdem/core/communicator.hpp"
#include "rcdem/solver/body_contacts.hpp"
#include "rcdem/solver/decomposition.hpp"
#include "rcdem/solver/step_part.hpp"
#include "rcdem/state/bodies.hpp"

namespace rcdem {

class ConcreteContacts final : public StepPart {
 public:
  // For the network `net` of the specimen whose bodies are `bodies` (at t = 0); `kinematics`: the
  // simulation's, read by the evaluation, the catch-up and the strain energy. Both must outlive
  // the part.
  ConcreteContacts(const Scenario& sc, const ContactNetwork& net, const Bodies& bodies,
                   const BodyKinematics& kinematics);

  void evaluate(const StepContext& ctx) override;
  // Assigns every body's force and torque (it visits every body: the first part in the list).
  void scatter(Bodies& bodies) const override;
  void add_dissipation(StepDissipation& d) const override;
  void add_strain_energy(Real& sum) const override;
  void visit_springs(SpringVisitor& v, const Bodies& bodies) const override;

  // A distributed run (solver/decomposition.hpp): evaluate the share `d` gives this rank, assign
  // the forces of its spheres (and of the bodies past them), and sum the strain energy over every
  // rank's blocks through `comm` (RankExchange shares the dissipation's).
  void distribute(const Decomposition& d, Communicator& comm);

  // Brings the histories of the contacts condensed at the last evaluation up to that step.
  void catch_up(Real dt) const;
  const ContactLaw& law() const { return law_; }
  // Mutable: condensed contacts' point histories are filled in when first read (logically const).
  ContactState& state() const { return contacts_; }
  const ElasticCondensation& condensation() const { return condensation_; }

  // A distributed run's held contacts, from every rank onto rank 0 for its checkpoint (after each
  // rank's catch-up: collective).
  void gather_held();

  // The checkpoint's "contacts" (core/archive.hpp). Restored: which contacts are intact follows
  // from the points' damage, and none is condensed (their histories were complete when saved);
  // the held ones (format 8 on) stay held, their points current (held_contacts.hpp), and the
  // softening clocks (format 9 on) run on. Formats 6's and 7's held rows (before contacts with
  // broken, then softening points were held) are not read: such a file restarts with nothing
  // held, as formats 4 and 5 do (its points were caught up when written); before format 9 every
  // clock restarts at 0.
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& s) {
    ContactState::serialize(ar, "contacts", s.contacts_);
    HeldRows rows;
    bool with_held = true, with_clock = true;  // formats 8 and 9 on (above)
    if constexpr (Archive::loading) {
      with_held = ar.version() >= 8;
      with_clock = ar.version() >= 9;
    } else {
      s.held_rows(rows);
    }
    if (with_held) {
      ar.list("contacts.held", rows.held, member("contact", "-", &HeldRow::contact),
              member("sums", "", &HeldRow::sums));
      ar.list("contacts.held.entry", rows.entry, member("point", "-", &HeldEntryRow::point),
              member("history", "", &HeldEntryRow::history));
    }
    if (with_clock)
      ar.list("contacts.held.clock", rows.clock, member("contact", "-", &SofteningClockRow::contact),
              member("clock", "-", &SofteningClockRow::clock));
    if constexpr (Archive::loading) {
      if (ar.applying()) s.energy_kept_ = false;
      if (ar.applying()) {
        if (const std::string why = s.held_rows_fault(rows); !why.empty())
          ar.reject("section 'contacts.held': " + why);
        if (!s.condensation_.sums.empty()) {
          s.condensation_.reset_flags(*s.net_, s.contacts_.point.damage());
          s.apply_held_rows(rows);
        }
      }
    }
  }

 private:
  ContactInputs inputs(const std::vector<Vec3>& positions,
                       const std::vector<Eigen::Matrix3d>& rotation, Real dt) const;
  Real held_energy(Index c) const;  // held contact c's at the last evaluation
  // The held contacts' rows, ascending (after a read's catch-up: every one's entry saved), with
  // the non-zero softening clocks: this rank's own; rank 0 of a distributed run, every rank's
  // (gather_held).
  void held_rows(HeldRows& rows) const;
  // ... of contacts [lo, hi) evaluated on this rank, appended.
  void local_held_rows(Index lo, Index hi, HeldRows& rows) const;
  // What is wrong with restored rows (empty: nothing): contacts out of range or not ascending,
  // entry points not exactly the held contacts' points in order, a clock out of its range, or any
  // held with condensation off.
  std::string held_rows_fault(const HeldRows& rows) const;
  // The rows of the contacts this rank evaluates held again, their points current, their clocks
  // set.
  void apply_held_rows(const HeldRows& rows);
  // Held contact c with broken points: the condensation's sums hold_contact gave it, from its
  // points' histories at entry.
  void restore_broken_point_sums(Index c, const std::vector<PlanePointState>& entry);

  // A distributed run's: the ranks, the strain energy's blocks per rank, the spheres this rank
  // assigns (then every body from `scatter_spheres_end_`), all of them when not distributed.
  Communicator* comm_ = nullptr;
  std::vector<Index> energy_block_offsets_;
  Index scatter_begin_ = 0, scatter_spheres_end_ = 0, spheres_ = 0;

  const ContactNetwork* net_;
  const Bodies* bodies_;
  const BodyKinematics* kinematics_;
  ContactLaw law_;  // contact.law
  mutable ContactState contacts_;
  mutable ElasticCondensation condensation_;  // empty when off or for a law that does not opt in
  BodyContacts body_contacts_;
  mutable std::vector<Real> strain_energy_blocks_;  // the strain energy's per-block sums
  // Per contact, kept by the last evaluation when it was asked to (StepContext): energy_kept_.
  std::vector<Real> contact_energy_;
  bool energy_kept_ = false;
  std::vector<Index> own_contacts_;  // distributed: each rank's own contacts (ranks + 1 offsets)
  // Rank 0 of a distributed run: every rank's held rows at the last gather (gather_held).
  HeldRows gathered_held_;
};

}  // namespace rcdem
