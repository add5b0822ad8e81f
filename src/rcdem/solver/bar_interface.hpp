#pragma once
// One bar's steel-concrete interface as a part of the step (solver/step_part.hpp; SPEC 8, paper
// 3): its contacts between concrete particles and the bar's cylinders, with the bar's law (EL,
// NL-A, NL-B). Evaluated in small tasks beside the other small parts.
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/contact/contact_state.hpp"
#include "rcdem/contact/laws/law_registry.hpp"
#include "rcdem/solver/step_part.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

class BarInterface final : public StepPart {
 public:
  static constexpr Index kTaskSize = 64;  // contacts per task

  // The specimen's interface `index`, of the bar `settings`, with its contacts `ic` (which must
  // outlive the part), whose cylinders are among `bodies` at t = 0.
  BarInterface(std::size_t index, const BarSettings& settings, const ContactParameters& contact,
               const InterfaceContacts& ic, const Bodies& bodies);

  Index task_count() const override;
  void run_task(Index task, const StepContext& ctx) override;
  void scatter(Bodies& bodies) const override;
  void add_dissipation(StepDissipation& d) const override;
  void add_strain_energy(Real& sum) const override;
  void visit_springs(SpringVisitor& v, const Bodies& bodies) const override;

  const ContactState& state() const { return state_; }
  const ContactNetwork& network() const { return ic_->net; }

  // The checkpoint's "interface.<bar>" (core/archive.hpp).
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& s) {
    ContactState::serialize(ar, "interface." + std::to_string(s.index_), s.state_);
  }

 private:
  std::size_t index_;
  const InterfaceContacts* ic_;
  ContactLaw law_;
  ContactState state_;
};

}  // namespace rcdem
