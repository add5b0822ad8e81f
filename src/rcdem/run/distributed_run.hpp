#pragma once
// `mpirun -np N rcdem run` (docs/parallel.md): rank 0 runs the run as one process would (its
// directory, outputs, checkpoints, signals, messages) over a distributed simulation
// (Simulation::distribute); the other ranks build the same simulation, step their share when rank
// 0 steps, and send it what it writes. They write no file and print only a failure of their own.
#include <string>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/communicator.hpp"

namespace rcdem {

class Simulation;

// The ranks of one run, as rank 0 tells the others what to do.
class RankGroup {
 public:
  explicit RankGroup(Communicator& comm) : comm_(&comm) {}
  Communicator& comm() const { return *comm_; }

  // Rank 0, before it builds: the others build from `sc` too.
  void start(const Scenario& sc);
  // Every rank, once built (`failure`: this rank's error, empty if none): true if every rank
  // built; rank 0 throws the first other rank's error when only others failed.
  bool built(const std::string& failure);
  // Rank 0: the checkpoint `file` (scenario hash `hash`) that `sim` was restored from.
  void restored(const Simulation& sim, const std::string& file, std::uint64_t hash);
  // Rank 0, when the run has ended (exit code 0) or failed (1): the others end with it. Once.
  void finish(int code);

 private:
  Communicator* comm_;
  bool finished_ = false;
};

// The other ranks' whole run: waits for rank 0's start, builds, follows; returns the exit code.
int follow_run(RankGroup& group, int threads);

// Rank 0's text to every rank.
std::string broadcast_text(Communicator& comm, const std::string& text);

}  // namespace rcdem
