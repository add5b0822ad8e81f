#pragma once
// core/communicator.hpp over MPI's world communicator (built with the `mpi` preset only), and the
// process's MPI session: initialised only when a launcher (mpirun, srun) started this process, so
// that the same binary runs alone without one.
#include "rcdem/core/communicator.hpp"

namespace rcdem {

class MpiSession {
 public:
  // Initialises MPI (threads: only the main thread calls it) if a launcher started the process.
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  bool active() const { return active_; }
  int size() const;
  int rank() const;  // 0 when not launched by MPI

 private:
  bool active_ = false;
};

class MpiCommunicator final : public Communicator {
 public:
  MpiCommunicator();
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void allgather(void* data, std::size_t bytes, const std::vector<Index>& offsets) override;
  void gather(void* data, std::size_t bytes, const std::vector<Index>& offsets) override;
  void broadcast(void* data, std::size_t bytes) override;
  void gather_bytes(const std::vector<std::uint8_t>& local,
                    std::vector<std::uint8_t>& all) override;
  void all_to_all(const std::vector<std::uint8_t>& send, const std::vector<Index>& counts_out,
                  std::vector<std::uint8_t>& recv, const std::vector<Index>& counts_in) override;
  void sum(std::int64_t* values, int count) override;
  [[noreturn]] void abort(int code) override;

 private:
  int rank_ = 0, size_ = 1;
  std::vector<int> count_, displ_;                      // gather_bytes's, kept between calls
  std::vector<int> scount_, sdispl_, rcount_, rdispl_;  // all_to_all's
};

}  // namespace rcdem
