#pragma once
// The one loop construct for hot loops (in the manner of MFEM's forall): serial or OpenMP now,
// with kernel bodies written so that a CUDA back end can reuse them. Bodies must not write to
// shared locations; reductions are gathers over per-item results, so results do not depend on the
// thread count.
#include <cstdint>

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

}  // namespace rcdem
