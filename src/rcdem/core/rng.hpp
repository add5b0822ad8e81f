#pragma once
// Seeded random numbers whose sequence is fixed by this file alone. std::uniform_real_distribution
// is implementation-defined, so the same seed could give another packing with another standard
// library; the 53-bit conversion below cannot.
#include <cstdint>
#include <random>

namespace rcdem {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  // Uniform in [0, 1).
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace rcdem
