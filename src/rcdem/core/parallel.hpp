#pragma once
// The one loop construct for hot loops (in the manner of MFEM's forall): serial or OpenMP now,
// with kernel bodies written so that a CUDA back end can reuse them. Bodies must not write to
// shared locations; reductions are gathers over per-item results, so results do not depend on the
// thread count.
#include <cstdint>
#include <vector>

namespace rcdem {

// Below this many items a loop runs serially: a parallel region's barrier costs more than the
// work, and far more when another job holds a core.
inline constexpr std::int64_t kParallelMinItems = 2048;

template <typename Body>
void parallel_for(std::int64_t n, Body&& body) {
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) if (n >= kParallelMinItems)
  for (std::int64_t i = 0; i < n; ++i) body(i);
#else
  for (std::int64_t i = 0; i < n; ++i) body(i);
#endif
}

// The same over blocks of `block` consecutive items, body(begin, end), handed out as threads
// become free: for loops whose items cost unequal amounts (the contacts of a cracked region visit
// their points, the others only their sums), 4 blocks at a time, so that a thread's next block is
// usually its own (the condensed contacts' kernel prefetches into it). The blocks are fixed by the
// item numbers, so which thread runs a block changes nothing in its results.
template <typename Body>
void parallel_for_blocks(std::int64_t n, std::int64_t block, Body&& body) {
  const std::int64_t blocks = (n + block - 1) / block;
#if defined(_OPENMP)
#pragma omp parallel for schedule(dynamic, 4) if (n >= kParallelMinItems)
#endif
  for (std::int64_t k = 0; k < blocks; ++k) {
    const std::int64_t begin = k * block;
    body(begin, begin + block < n ? begin + block : n);
  }
}

// parallel_for_blocks over only the blocks listed in `*blocks` (block numbers, ascending; none
// may be listed): a distributed run's share of a loop (solver/decomposition.hpp); every block of n
// when `blocks` is null.
template <typename Body>
void parallel_for_listed_blocks(const std::vector<std::int64_t>* blocks, std::int64_t n,
                                std::int64_t block, Body&& body) {
  if (!blocks) {
    parallel_for_blocks(n, block, body);
    return;
  }
  const auto count = static_cast<std::int64_t>(blocks->size());
#if defined(_OPENMP)
#pragma omp parallel for schedule(dynamic, 4) if (count * block >= kParallelMinItems)
#endif
  for (std::int64_t k = 0; k < count; ++k) {
    const std::int64_t begin = (*blocks)[static_cast<std::size_t>(k)] * block;
    body(begin, begin + block < n ? begin + block : n);
  }
}

// n tasks, each known to be worth a thread (a block of the small networks' contacts), handed out
// one at a time: in parallel from two tasks on, where parallel_for's threshold counts items. Each
// task writes only its own outputs, so which thread runs it changes nothing.
template <typename Body>
void parallel_tasks(std::int64_t n, Body&& body) {
#if defined(_OPENMP)
#pragma omp parallel for schedule(dynamic, 1) if (n > 1)
#endif
  for (std::int64_t k = 0; k < n; ++k) body(k);
}

}  // namespace rcdem
