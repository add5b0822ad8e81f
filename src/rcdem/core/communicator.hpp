#pragma once
// The ranks of a distributed run (docs/parallel.md) as the step and the run loop use them, without
// MPI's types: the library builds and runs without MPI, and mpi/mpi_communicator implements this
// where the `mpi` preset builds it. Every call is collective: each rank makes the same calls in the
// same order.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rcdem/core/types.hpp"

namespace rcdem {

class Communicator {
 public:
  virtual ~Communicator() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  bool leader() const { return rank() == 0; }

  // `data` holds the same array of `bytes`-byte elements on every rank, and rank r owns its
  // elements [offsets[r], offsets[r + 1]) (offsets: size() + 1 entries, ascending). After the
  // call every rank (allgather) or rank 0 (gather) holds every rank's own elements.
  virtual void allgather(void* data, std::size_t bytes, const std::vector<Index>& offsets) = 0;
  virtual void gather(void* data, std::size_t bytes, const std::vector<Index>& offsets) = 0;
  // Rank 0's `bytes` bytes at `data` to every rank.
  virtual void broadcast(void* data, std::size_t bytes) = 0;
  // Each rank's `local` appended in rank order into rank 0's `all` (resized; the others' is left
  // empty).
  virtual void gather_bytes(const std::vector<std::uint8_t>& local,
                            std::vector<std::uint8_t>& all) = 0;
  // Rank r's `send[counts_out[k], counts_out[k + 1])` bytes go to rank k (counts_out: byte
  // offsets, size() + 1 entries), and rank k's to r arrive in `recv` at r's offsets `counts_in`.
  virtual void all_to_all(const std::vector<std::uint8_t>& send,
                          const std::vector<Index>& counts_out, std::vector<std::uint8_t>& recv,
                          const std::vector<Index>& counts_in) = 0;
  // Every rank's `values` summed element by element, on every rank (integers: exact, so the
  // result does not depend on the order the ranks are combined in).
  virtual void sum(std::int64_t* values, int count) = 0;
  // Ends every rank's process with `code` (a failure on this rank alone: no other rank may wait
  // for it).
  [[noreturn]] virtual void abort(int code) = 0;

  // The same for a vector-like `v` (data(), element type).
  template <class V>
  void allgather(V& v, const std::vector<Index>& offsets) {
    allgather(v.data(), sizeof(*v.data()), offsets);
  }
  template <class V>
  void gather(V& v, const std::vector<Index>& offsets) {
    gather(v.data(), sizeof(*v.data()), offsets);
  }
  template <class T>
  void broadcast(T& value) {
    broadcast(&value, sizeof(T));
  }
};

}  // namespace rcdem
