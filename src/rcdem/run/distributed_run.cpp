#include "rcdem/run/distributed_run.hpp"

#include <fmt/format.h>

#include <cstring>
#include <optional>
#if defined(_OPENMP)
#include <omp.h>
#endif

#include "rcdem/core/error.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"

namespace rcdem {

std::string broadcast_text(Communicator& comm, const std::string& text) {
  std::int64_t size = static_cast<std::int64_t>(text.size());
  comm.broadcast(size);
  std::string out = comm.leader() ? text : std::string(static_cast<std::size_t>(size), '\0');
  if (size > 0) comm.broadcast(out.data(), out.size());
  return out;
}

namespace {

RankMessage exchange(Communicator& comm, RankMessage m) {
  comm.broadcast(m);
  return m;
}

}  // namespace

void RankGroup::start(const Scenario& sc) {
  exchange(*comm_, {RankCommand::Start, 0});
  broadcast_text(*comm_, sc.text);
  broadcast_text(*comm_, sc.source.string());
}

bool RankGroup::built(const std::string& failure) {
  std::vector<std::uint8_t> mine(failure.begin(), failure.end());
  mine.push_back(0);
  std::vector<std::uint8_t> all;
  comm_->gather_bytes(mine, all);
  std::int64_t failed = failure.empty() ? 0 : 1;
  comm_->sum(&failed, 1);
  if (!comm_->leader()) return failed == 0;
  if (failed == 0) return true;
  finished_ = true;                    // the others have ended
  if (!failure.empty()) return false;  // rank 0's own error, which its caller throws
  // The first rank that failed, with its message.
  std::size_t at = 0;
  for (int r = 0; r < comm_->size(); ++r) {
    const auto* text = reinterpret_cast<const char*>(all.data() + at);
    const std::size_t n = std::strlen(text);
    if (n > 0) fail("rank {} of {} failed to build the simulation: {}", r, comm_->size(), text);
    at += n + 1;
  }
  return true;
}

void RankGroup::restored(const Simulation& sim, const std::string& file, std::uint64_t hash) {
  std::int64_t value = 0;
  std::memcpy(&value, &hash, sizeof(value));
  sim.tell_ranks(RankCommand::Restore, value);
  broadcast_text(*comm_, file);
}

void RankGroup::finish(int code) {
  if (finished_ || !comm_->leader()) return;
  finished_ = true;
  exchange(*comm_, {RankCommand::Finish, code});
}

int follow_run(RankGroup& group, int threads) {
#if defined(_OPENMP)
  if (threads > 0) omp_set_num_threads(threads);
#else
  (void)threads;
#endif
  Communicator& comm = group.comm();
  const RankMessage first = exchange(comm, {});
  if (first.command != RankCommand::Start) return static_cast<int>(first.value);
  const std::string text = broadcast_text(comm, "");
  const std::string source = broadcast_text(comm, "");
  std::optional<Simulation> sim;
  std::string failure;
  try {
    Scenario sc = parse_scenario(text, source);
    sim.emplace(sc, build_specimen(sc));
    sim->distribute(comm);
  } catch (const std::exception& e) {
    failure = e.what();
    if (failure.empty()) failure = "unknown error";
  }
  if (!group.built(failure)) return 1;
  for (;;) {
    const RankMessage m = sim->follow();
    if (m.command == RankCommand::Finish) return static_cast<int>(m.value);
    if (m.command != RankCommand::Restore)
      fail("rank {}: unexpected request {} from rank 0", comm.rank(),
           static_cast<std::int64_t>(m.command));
    const std::string file = broadcast_text(comm, "");
    std::uint64_t hash = 0;
    std::memcpy(&hash, &m.value, sizeof(hash));
    io::restore_checkpoint(file, io::CheckpointParts{&*sim}, hash);
  }
}

}  // namespace rcdem
