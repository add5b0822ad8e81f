#include "rcdem/core/simd_level.hpp"

#include <cstdlib>
#include <cstring>

namespace rcdem {

namespace {

SimdLevel detect() {
#if RCDEM_SIMD_MULTIVERSION
  __builtin_cpu_init();
  SimdLevel level = __builtin_cpu_supports("avx512f") ? SimdLevel::Avx512
                    : __builtin_cpu_supports("avx2")  ? SimdLevel::Avx2
                                                      : SimdLevel::Baseline;
  if (const char* cap = std::getenv("RCDEM_SIMD")) {
    const SimdLevel most = std::strcmp(cap, "baseline") == 0 ? SimdLevel::Baseline
                           : std::strcmp(cap, "avx2") == 0   ? SimdLevel::Avx2
                                                             : SimdLevel::Avx512;
    if (most < level) level = most;
  }
  return level;
#else
  return SimdLevel::Baseline;
#endif
}

}  // namespace

SimdLevel simd_level() {
  static const SimdLevel level = detect();
  return level;
}

const char* simd_level_name(SimdLevel level) {
  switch (level) {
    case SimdLevel::Avx2:
      return "avx2";
    case SimdLevel::Avx512:
      return "avx512";
    default:
      return "baseline";
  }
}

}  // namespace rcdem
