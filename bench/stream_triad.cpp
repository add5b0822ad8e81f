// STREAM triad (McCalpin): a[i] = b[i] + s * c[i] over three arrays of doubles well above the
// last-level cache, OpenMP static schedule (the same partition as rcdem's parallel_for), first
// touch in parallel so each thread's pages sit near it. Best of 10 repetitions. Bytes counted as
// STREAM does: 3 x 8 per element (two reads, one write; no write-allocate traffic counted).
// Usage: rcdem_stream [ELEMENTS=4e7]   (4e7 elements: 3 x 320 MB)
// Prints: stream_triad_GBps=<x> (and the elements, threads, best seconds).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>

#if defined(_OPENMP)
#include <omp.h>
#endif

int main(int argc, char** argv) {
  const long long n = argc > 1 ? static_cast<long long>(std::strtod(argv[1], nullptr)) : 40000000LL;
  if (n <= 0) {
    std::fprintf(stderr, "usage: rcdem_stream [ELEMENTS=4e7]\n");
    return 1;
  }
  // new double[n] leaves the pages untouched: the parallel init below places them.
  std::unique_ptr<double[]> a(new double[static_cast<std::size_t>(n)]);
  std::unique_ptr<double[]> b(new double[static_cast<std::size_t>(n)]);
  std::unique_ptr<double[]> c(new double[static_cast<std::size_t>(n)]);
  double* pa = a.get();
  double* pb = b.get();
  double* pc = c.get();
#pragma omp parallel for schedule(static)
  for (long long i = 0; i < n; ++i) {
    pa[i] = 1.0;
    pb[i] = 2.0;
    pc[i] = 0.5;
  }
  const double s = 3.0;
  double best = std::numeric_limits<double>::infinity();
  for (int rep = 0; rep < 10; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static)
    for (long long i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    const auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count());
  }
  // Check the result so the loop cannot be dropped: every a[i] = 2 + 3 * 0.5 = 3.5.
  double sum = 0.0;
  for (long long i = 0; i < n; i += 4096) sum += pa[i];
  const long long checked = (n + 4095) / 4096;
  if (sum != 3.5 * static_cast<double>(checked)) {
    std::fprintf(stderr, "rcdem_stream: wrong triad result\n");
    return 2;
  }
  int threads = 1;
#if defined(_OPENMP)
  threads = omp_get_max_threads();
#endif
  const double bytes = 3.0 * 8.0 * static_cast<double>(n);
  std::printf("stream_elements=%lld stream_threads=%d stream_best_seconds=%.6f stream_triad_GBps=%.3f\n",
              n, threads, best, bytes / best * 1e-9);
  return 0;
}
