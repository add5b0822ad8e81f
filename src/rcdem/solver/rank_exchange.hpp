#pragma once
// What the ranks of a distributed run exchange (docs/parallel.md; the shares are
// solver/decomposition.hpp's): every step, the spheres each rank moved and its contacts' crack
// record; on rank 0's request, the whole state it writes (snapshots, checkpoints). Every call is
// collective (core/communicator.hpp).
#include <array>
#include <cstdint>
#include <vector>

#include "rcdem/contact/contact_state.hpp"
#include "rcdem/core/communicator.hpp"
#include "rcdem/solver/body_step_sums.hpp"
#include "rcdem/solver/decomposition.hpp"
#include "rcdem/state/bodies.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

// What rank 0 asks of the others between steps (Simulation::follow serves Step to GatherMotion
// and KeepStrainEnergy; the run loop the rest).
enum class RankCommand : std::int64_t {
  Start = 1,  // the run loop's: the scenario follows; build the simulation
  Step,
  StrainEnergy,      // the ledger's strain energy (its concrete blocks gathered)
  GatherState,       // every contact, point and body state, onto rank 0
  GatherMotion,      // every sphere's motion onto rank 0 (what its outputs read)
  ExchangeTimes,     // every rank's exchange time by kind onto rank 0
  KeepStrainEnergy,  // value: Simulation::keep_strain_energy_every's n
  Restore,           // the run loop's: a checkpoint's path follows
  Finish,            // the run ended: value 0, or 1 after an error rank 0 reports
};
struct RankMessage {
  RankCommand command = RankCommand::Finish;
  std::int64_t value = 0;
};

// The counters and log length of a ContactState before a step's tally.
struct TallyMark {
  Index damaged_or_broken = 0, broken = 0;
  std::size_t log = 0;
  static TallyMark of(const ContactState& cs) {
    return {cs.damaged_or_broken, cs.broken, cs.broken_contact_log.size()};
  }
};

// What a rank's exchange time is spent on: rank 0's commands, the dissipation sums, the crack
// log, the ghosts and the integrator's sums, rank 0's requests for the motion and the state (the
// strain energy's block sums are gathered by the concrete contacts themselves: not counted).
enum class ExchangeKind { Command, Dissipation, CrackLog, Spheres, Requests, Count };
inline constexpr const char* kExchangeKindNames[] = {"command", "dissipation", "crack_log",
                                                     "spheres", "requests"};
using ExchangeSeconds = std::array<double, static_cast<std::size_t>(ExchangeKind::Count)>;

class RankExchange {
  friend class ExchangeTimer;

 public:
  // `net`: the concrete network the decomposition splits; `shared`: the spheres every rank reads
  // (those of the parts every rank evaluates: the bars' interfaces, the plates' contacts).
  RankExchange(Communicator& comm, Decomposition d, const ContactNetwork& net,
               const std::vector<Index>& shared);
  Communicator& comm() const { return *comm_; }
  const Decomposition& decomposition() const { return d_; }
  bool leader() const { return comm_->leader(); }

  // After the integration: each rank's spheres' motion to the ranks that read them (its ghosts
  // elsewhere), and the integrator's block sums to every rank: each rank then holds what it reads
  // as a serial run would. Rank 0 reads only its ghosts too; what it writes it gathers on demand
  // (gather_motion).
  void share_spheres(Bodies& b, BodyStepSums& sums) const;
  // After the evaluation: each rank's dissipation sums (per block of the loop, or per contact
  // without condensation) to every rank, for the ledger.
  void share_dissipation(ContactState& cs) const;
  // The integrator's per-body instability flags, to every rank (for the message).
  void share_jumps(BodyStepSums& sums) const;
  // After a step's tally: every rank's new transitions and crack log onto rank 0, the log in
  // contact order with the broken contacts' point records, as a serial step would have left
  // them. The other ranks' logs are emptied.
  void gather_transitions(ContactState& cs, const ContactNetwork& net,
                          const TallyMark& before) const;
  // Every sphere's motion (position, velocity, spin, orientation, angular momentum) onto rank 0.
  void gather_motion(Bodies& b) const;
  // The bodies this rank's parts read: its own spheres, its ghosts, every bar cylinder (ascending).
  std::vector<Index> read_bodies(Index bodies) const;
  // Every contact's and point's state, the bodies' motion and forces and the per-body step sums
  // onto rank 0.
  void gather_state(ContactState& cs, const ContactNetwork& net, Bodies& b,
                    BodyStepSums& sums) const;
  // Rank 0's message to every rank (the others receive it).
  RankMessage exchange(RankMessage m) const;
  // Wall time this rank has spent in the step's exchanges (waiting for the others included) and
  // in rank 0's requests since the last reset, by kind.
  void reset_seconds() const { seconds_.fill(0.0); }
  // Every rank's exchange time by kind, in rank order, on rank 0 (collective).
  std::vector<ExchangeSeconds> gather_seconds() const;

 private:
  Communicator* comm_;
  Decomposition d_;
  // The ranges in the loop's and the integrator's blocks; the crack log's messages (kept, so that
  // a step allocates nothing once they have grown).
  std::vector<Index> contact_blocks_, sphere_blocks_;
  // The ghosts: the spheres this rank sends to each rank and receives from each, in rank order,
  // and their byte offsets in the messages.
  std::vector<Index> send_, receive_, send_bytes_, receive_bytes_;
  mutable std::vector<std::uint8_t> out_, in_;
  mutable std::vector<std::uint8_t> mine_, all_;
  mutable ExchangeSeconds seconds_{};
};

}  // namespace rcdem
