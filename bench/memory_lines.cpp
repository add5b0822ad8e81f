// What one thread pays for a cache line of memory far above the last-level cache, three ways:
//   read_ns_per_line   a sequential read (every double summed): the hardware prefetchers' best;
//   random_ns_per_line independent reads of one word from lines at random (their addresses known
//                      ahead, as a gather's are): what the core keeps in flight sets it;
//   latency_ns         a chase, each line's address in the last one read: the latency alone.
// Each in 4 KiB pages and in 2 MiB pages (the buffer advised MADV_HUGEPAGE before it is touched;
// `huge_kib` says how much of it the kernel gave). The cracked step's floor (bench/step_floor.py)
// is its scattered lines at random_ns_per_line and the rest of its bytes at the sequential rate.
// Usage: rcdem_memory_lines [MIB=512]
// Prints one line per page size: page=4k|2m read_ns_per_line=... random_ns_per_line=...
// latency_ns=... huge_kib=...
#include <sys/mman.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace {

constexpr std::size_t kLine = 64;
constexpr std::size_t kHugePage = std::size_t{2} << 20;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The smallest of `reps` timings of f().
template <class F>
double best_of(int reps, F f) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < reps; ++r) best = std::min(best, f());
  return best;
}

double read_ns_per_line(const char* buf, std::size_t bytes) {
  const auto* d = reinterpret_cast<const double*>(buf);
  const std::size_t n = bytes / sizeof(double);
  return best_of(3, [&] {
    const auto t0 = std::chrono::steady_clock::now();
    double s[8] = {};
    for (std::size_t i = 0; i + 8 <= n; i += 8)
      for (int k = 0; k < 8; ++k) s[k] += d[i + static_cast<std::size_t>(k)];
    const double t = seconds_since(t0);
    double sum = 0.0;
    for (const double v : s) sum += v;
    asm volatile("" : : "x"(sum));
    return t / static_cast<double>(bytes / kLine) * 1e9;
  });
}

double random_ns_per_line(const char* buf, const std::vector<std::uint64_t>& offsets) {
  return best_of(3, [&] {
    std::uint64_t any = 0, word;
    const auto t0 = std::chrono::steady_clock::now();
    for (const std::uint64_t o : offsets) {
      std::memcpy(&word, buf + o, sizeof word);
      any |= word;
    }
    const double t = seconds_since(t0);
    asm volatile("" : : "r"(any));
    return t / static_cast<double>(offsets.size()) * 1e9;
  });
}

double latency_ns(char* buf, std::size_t lines, std::mt19937_64& rng) {
  std::vector<std::uint64_t> order(lines);
  std::iota(order.begin(), order.end(), std::uint64_t{0});
  std::shuffle(order.begin(), order.end(), rng);
  for (std::size_t i = 0; i < lines; ++i) {
    const std::uint64_t next = order[(i + 1) % lines] * kLine;
    std::memcpy(buf + order[i] * kLine, &next, sizeof next);
  }
  constexpr std::size_t kChase = 2000000;
  return best_of(2, [&] {
    std::uint64_t at = order[0] * kLine;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < kChase; ++k) std::memcpy(&at, buf + at, sizeof at);
    const double t = seconds_since(t0);
    asm volatile("" : : "r"(at));
    return t / kChase * 1e9;
  });
}

long long anon_huge_kib() {
  std::ifstream in("/proc/self/smaps_rollup");
  std::string key;
  long long v = 0;
  while (in >> key) {
    if (key == "AnonHugePages:" && in >> v) return v;
    in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return 0;
}

void measure(std::size_t bytes, bool huge) {
  char* buf = static_cast<char*>(std::aligned_alloc(kHugePage, bytes));
  if (!buf) {
    std::fprintf(stderr, "rcdem_memory_lines: cannot allocate %zu bytes\n", bytes);
    std::exit(1);
  }
  ::madvise(buf, bytes, huge ? MADV_HUGEPAGE : MADV_NOHUGEPAGE);
  std::memset(buf, 1, bytes);  // first touch, after the advice
  const long long huge_kib = anon_huge_kib();
  const std::size_t lines = bytes / kLine;
  std::mt19937_64 rng(1);
  std::vector<std::uint64_t> offsets(4000000);
  for (auto& o : offsets) o = (rng() % lines) * kLine;
  const double read = read_ns_per_line(buf, bytes);
  const double random = random_ns_per_line(buf, offsets);
  const double latency = latency_ns(buf, lines, rng);
  std::printf(
      "page=%s read_ns_per_line=%.3f read_GBps=%.2f random_ns_per_line=%.3f latency_ns=%.1f "
      "huge_kib=%lld mib=%zu\n",
      huge ? "2m" : "4k", read, kLine / read, random, latency, huge_kib, bytes >> 20);
  std::free(buf);
}

}  // namespace

int main(int argc, char** argv) {
  const long mib = argc > 1 ? std::strtol(argv[1], nullptr, 10) : 512;
  if (mib < 64 || mib > 65536) {
    std::fprintf(stderr, "usage: rcdem_memory_lines [MIB=512] (64 to 65536)\n");
    return 1;
  }
  const std::size_t bytes = static_cast<std::size_t>(mib) << 20;
  measure(bytes, false);
  measure(bytes, true);
}
