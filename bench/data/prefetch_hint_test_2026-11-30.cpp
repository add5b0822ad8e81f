// A throw-away test behind bench/RESULTS.md (issue 43, 2026-11-30), not part of the build: how
// long a line requested with a prefetch hint stays in the caches on this machine.
//   g++ -O2 -march=native -o t bench/data/prefetch_hint_test_2026-11-30.cpp
//   ./t HINT N WORK   (HINT: -1 none, 0..3 = __builtin_prefetch locality 0..3, 4 = a load)
// Log: bench/data/issue43_tries_2026-11-30.txt.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>
#include <random>
#include <cstdint>
// 512 MB of lines; batches of N random lines: prefetch (hint H) them, burn ~W us of ALU, then load
// them (sum) and time the loads.
int main(int argc, char** argv) {
  const int hint = atoi(argv[1]);  // -1 none, 0 nta, 1 t2, 2 t1, 3 t0
  const int n = atoi(argv[2]);
  const int work = atoi(argv[3]);
  const size_t lines = (512u << 20) / 64;
  std::vector<double> a(lines * 8, 1.0);
  std::mt19937_64 rng(1);
  std::vector<size_t> idx(n);
  double sink = 0, t_load = 0;
  const int reps = 2000;
  for (int r = 0; r < reps; ++r) {
    for (auto& i : idx) i = (rng() % lines) * 8;
    for (auto i : idx) {
      switch (hint) {
        case 0: __builtin_prefetch(&a[i], 0, 0); break;
        case 1: __builtin_prefetch(&a[i], 0, 1); break;
        case 2: __builtin_prefetch(&a[i], 0, 2); break;
        case 3: __builtin_prefetch(&a[i], 0, 3); break;
        case 4: sink += a[i]; break;
        default: break;
      }
    }
    double x = 1.0;
    for (int k = 0; k < work * 300; ++k) x = x * 1.0000001 + 1e-9;
    sink += x;
    auto t0 = std::chrono::steady_clock::now();
    double s = 0;
    for (auto i : idx) s += a[i];
    auto t1 = std::chrono::steady_clock::now();
    sink += s;
    t_load += std::chrono::duration<double>(t1 - t0).count();
  }
  printf("hint=%d n=%d work=%d: %.2f ns per line (sink %g)\n", hint, n, work, t_load / reps / n * 1e9, sink);
}
