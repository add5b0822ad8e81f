#include "rcdem/mpi/mpi_communicator.hpp"

#include <mpi.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <limits>

#include "rcdem/core/error.hpp"
#include "rcdem/mpi/peer_watch.hpp"

namespace rcdem {

namespace {

std::atomic<std::int64_t> g_waiting_since{0};

// Marks the calling process as waiting in an MPI call while in scope (PeerWatch reads it).
struct Waiting {
  Waiting() {
    g_waiting_since.store(std::chrono::duration_cast<std::chrono::nanoseconds>(
                              std::chrono::steady_clock::now().time_since_epoch())
                              .count(),
                          std::memory_order_relaxed);
  }
  ~Waiting() { g_waiting_since.store(0, std::memory_order_relaxed); }
  Waiting(const Waiting&) = delete;
  Waiting& operator=(const Waiting&) = delete;
};

// Launchers' environment: Open MPI's mpirun, PMIx (Slurm's srun, Open MPI 5), MPICH's Hydra.
bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

// Element counts and displacements of the ranges `offsets` describes.
void counts_of(const std::vector<Index>& offsets, int size, std::vector<int>& count,
               std::vector<int>& displ) {
  if (static_cast<int>(offsets.size()) != size + 1)
    fail("internal error: {} offsets for {} ranks", offsets.size(), size);
  count.resize(static_cast<std::size_t>(size));
  displ.resize(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r) {
    const auto k = static_cast<std::size_t>(r);
    if (offsets[k + 1] < offsets[k] || offsets[k + 1] > std::numeric_limits<int>::max())
      fail("internal error: rank {}'s range [{}, {})", r, offsets[k], offsets[k + 1]);
    count[k] = static_cast<int>(offsets[k + 1] - offsets[k]);
    displ[k] = static_cast<int>(offsets[k]);
  }
}

// A datatype of `bytes` contiguous bytes: the element counts stay those of the arrays.
struct Element {
  MPI_Datatype type{};
  explicit Element(std::size_t bytes) {
    MPI_Type_contiguous(static_cast<int>(bytes), MPI_BYTE, &type);
    MPI_Type_commit(&type);
  }
  ~Element() { MPI_Type_free(&type); }
  Element(const Element&) = delete;
  Element& operator=(const Element&) = delete;
};

}  // namespace

std::int64_t collective_waiting_since_ns() {
  return g_waiting_since.load(std::memory_order_relaxed);
}

MpiSession::MpiSession(int& argc, char**& argv) {
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  active_ = true;
}

MpiSession::~MpiSession() {
  if (active_) MPI_Finalize();
}

int MpiSession::size() const {
  int n = 1;
  if (active_) MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

int MpiSession::rank() const {
  int r = 0;
  if (active_) MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

MpiCommunicator::MpiCommunicator() {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

void MpiCommunicator::allgather(void* data, std::size_t bytes, const std::vector<Index>& offsets) {
  const Waiting waiting;
  std::vector<int> count, displ;
  counts_of(offsets, size_, count, displ);
  const Element e(bytes);
  MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, data, count.data(), displ.data(), e.type,
                 MPI_COMM_WORLD);
}

void MpiCommunicator::gather(void* data, std::size_t bytes, const std::vector<Index>& offsets) {
  const Waiting waiting;
  std::vector<int> count, displ;
  counts_of(offsets, size_, count, displ);
  const Element e(bytes);
  const auto r = static_cast<std::size_t>(rank_);
  if (rank_ == 0) {
    MPI_Gatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, data, count.data(), displ.data(), e.type, 0,
                MPI_COMM_WORLD);
    return;
  }
  auto* mine = static_cast<char*>(data) + static_cast<std::size_t>(displ[r]) * bytes;
  MPI_Gatherv(mine, count[r], e.type, nullptr, nullptr, nullptr, e.type, 0, MPI_COMM_WORLD);
}

void MpiCommunicator::broadcast(void* data, std::size_t bytes) {
  const Waiting waiting;
  MPI_Bcast(data, static_cast<int>(bytes), MPI_BYTE, 0, MPI_COMM_WORLD);
}

void MpiCommunicator::gather_bytes(const std::vector<std::uint8_t>& local,
                                   std::vector<std::uint8_t>& all) {
  const Waiting waiting;
  const int mine = static_cast<int>(local.size());
  count_.resize(static_cast<std::size_t>(size_));
  displ_.resize(count_.size());
  MPI_Gather(&mine, 1, MPI_INT, count_.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  all.clear();
  if (rank_ == 0) {
    std::int64_t total = 0;
    for (std::size_t r = 0; r < count_.size(); ++r) {
      displ_[r] = static_cast<int>(total);
      total += count_[r];
    }
    all.resize(static_cast<std::size_t>(total));
  }
  MPI_Gatherv(local.data(), mine, MPI_BYTE, all.data(), count_.data(), displ_.data(), MPI_BYTE, 0,
              MPI_COMM_WORLD);
}

void MpiCommunicator::all_to_all(const std::vector<std::uint8_t>& send,
                                 const std::vector<Index>& counts_out,
                                 std::vector<std::uint8_t>& recv,
                                 const std::vector<Index>& counts_in) {
  const Waiting waiting;
  counts_of(counts_out, size_, scount_, sdispl_);
  counts_of(counts_in, size_, rcount_, rdispl_);
  MPI_Alltoallv(send.data(), scount_.data(), sdispl_.data(), MPI_BYTE, recv.data(), rcount_.data(),
                rdispl_.data(), MPI_BYTE, MPI_COMM_WORLD);
}

void MpiCommunicator::sum(std::int64_t* values, int count) {
  const Waiting waiting;
  MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
}

void MpiCommunicator::abort(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);  // MPI_Abort does not return; this says so to the compiler
}

}  // namespace rcdem
