#pragma once
// A part of the step (issue 41; HOOMD's force computes and LAMMPS's fixes are the models): the
// concrete network, each bar's interface, the interaction nodes, the plates, the pulled bars.
// Each owns its state and its behaviour at every stage of Simulation::step (SPEC 4-6, 11):
//
//   evaluate     its forces from the bodies' poses: its own parallel loops (evaluate), or small
//                tasks that run with every other part's in one parallel region (run_task)
//   scatter      its forces into the bodies' (the first part in the list assigns, the rest add)
//   prescribe    the velocities it imposes on bodies over the next move (a pulled bar's cylinder)
//   drive        after the move: its external work and its own next move (plates)
//   ledger       its dissipation this step and, on demand, its strain energy
//
// and, once at t = 0, its springs for SPEC 6's time-step estimates. Its checkpoint sections are
// its `serialize` (core/archive.hpp), listed in solver/simulation_archive.hpp. Recipes:
// docs/architecture.md, "A part" and "A loading".
#include <cstdint>
#include <vector>

#include "rcdem/core/types.hpp"
#include "rcdem/state/bodies.hpp"
#include "rcdem/state/body_poses.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

struct Energy;

// The bodies' poses as every part's evaluation reads them, formed once at the start of a step,
// and the previous step's (a condensed concrete contact catches up from them: contact_loop.hpp).
struct BodyKinematics {
  std::vector<Vec3> position, position_prev;
  std::vector<Eigen::Matrix3d> rotation, rotation_prev;
  BodyPoses pose;  // the same with the centres, for the condensed contacts' kernel

  // The bodies a distributed rank's parts read (RankExchange::read_bodies): only theirs are
  // formed; empty: every body.
  std::vector<Index> only;

  explicit BodyKinematics(const Bodies& bodies);
  // Keeps the current as the previous and forms the current from `bodies`.
  void update(const Bodies& bodies);
};

// Where the step is: the time at its start, its length, and the adaptive loading rate's factor on
// every prescribed speed (solver/loading_rate.hpp).
struct StepClock {
  Real time, dt, rate;
  Real mid() const { return time + 0.5 * dt; }
};

// What a part's evaluation reads and writes.
struct StepContext {
  Bodies& bodies;
  const BodyKinematics& kinematics;
  StepClock clock;
  // This step's state will be reported (a history row): a part that can keep its strain energy
  // while evaluating does, so that add_strain_energy need not visit its contacts again.
  bool report_strain_energy = false;
};

// Velocities imposed on bodies over the next move: translation at `velocity`, no rotation, no
// damping (the integrator's rule for a driven body, solver/integrator.hpp).
struct PrescribedMotion {
  std::vector<std::int64_t> slot;  // per body: its entry in velocity, or -1
  std::vector<Vec3> velocity;

  explicit PrescribedMotion(Index bodies) : slot(static_cast<std::size_t>(bodies), -1) {}
  // Body `body` moves as its part prescribes from now on; returns its entry.
  std::size_t claim(Index body) {
    slot[static_cast<std::size_t>(body)] = static_cast<std::int64_t>(velocity.size());
    velocity.push_back(Vec3::Zero());
    return velocity.size() - 1;
  }
  bool driven(Index body) const { return slot[static_cast<std::size_t>(body)] >= 0; }
};

// A step's dissipation (SPEC 11), summed part by part in the ledger's fixed order.
struct StepDissipation {
  Real damage = 0.0, friction = 0.0, plastic = 0.0;
};

// Receives every spring of SPEC 6's time-step estimates at t = 0 (solver/time_step_springs.hpp).
class SpringVisitor {
 public:
  virtual ~SpringVisitor() = default;
  // Every local point of `net`, each with its contact's unit normal.
  virtual void network(const ContactNetwork& net, std::vector<Vec3> normal) = 0;
  // A spring k_n along n and k_s across it between two material points (a < 0: a fixed plate).
  virtual void spring(Index a, Index b, const Vec3& arm_a, const Vec3& arm_b, const Vec3& n,
                      Real kn, Real ks) = 0;
  virtual void rotational(Index a, Index b, const Eigen::Matrix3d& k) = 0;
};

class StepPart {
 public:
  virtual ~StepPart() = default;
  StepPart() = default;
  StepPart(const StepPart&) = delete;
  StepPart& operator=(const StepPart&) = delete;

  // Evaluation. A part with much work loops in parallel itself; a small one splits its items
  // into tasks of a few dozen, all parts' tasks run in one region (bar by bar each network was
  // below parallel_for's threshold and ran on one thread while the other waited).
  virtual void evaluate(const StepContext&) {}
  virtual Index task_count() const { return 0; }
  virtual void run_task(Index /*task*/, const StepContext&) {}
  virtual void finish_evaluation() {}  // after every task, serial: sums in a fixed order

  virtual void scatter(Bodies&) const {}
  virtual void prescribe(PrescribedMotion&, const StepClock&) {}
  virtual void drive(const Bodies&, const StepClock&, Energy& /*ledger*/) {}

  virtual void add_dissipation(StepDissipation&) const {}
  // Adds the strain energy its springs hold now, in a fixed order.
  virtual void add_strain_energy(Real& /*sum*/) const {}
  virtual void visit_springs(SpringVisitor&, const Bodies& /*at t = 0*/) const {}
};

}  // namespace rcdem
