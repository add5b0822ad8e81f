#pragma once
// The one loop construct for hot loops (in the manner of MFEM's forall): serial or OpenMP now,
// with kernel bodies written so that a CUDA back end can reuse them. Bodies must not write to
// shared locations; reductions are gathers over per-item results, so results do not depend on the
// thread count.
#include <cstdint>

namespace rcdem {

template <typename Body>
void parallel_for(std::int64_t n, Body&& body) {
#if defined(_OPENMP)
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) body(i);
#else
  for (std::int64_t i = 0; i < n; ++i) body(i);
#endif
}

}  // namespace rcdem
