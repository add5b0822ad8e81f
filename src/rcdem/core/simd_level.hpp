#pragma once
// Which SIMD instruction set the step's two lane kernels (the condensed contacts' block and the
// spheres' update) run with. The portable build targets the x86-64 baseline (SSE2: two doubles a
// lane group); each kernel is also compiled for AVX2 and AVX-512F and picked at run time, once.
// The kernels compute every lane on its own (no sum across lanes) and never contract a * b + c,
// and +, -, *, / and sqrt round alike at every width, so every level gives the same bits
// (tests/reproducibility/simd_levels.sh checks a run at each level byte for byte).
namespace rcdem {

enum class SimdLevel { Baseline = 0, Avx2 = 1, Avx512 = 2 };

// The widest level this CPU supports, capped by the environment variable RCDEM_SIMD ("baseline",
// "avx2" or "avx512"; for tests and comparisons). Always Baseline outside x86-64 GCC/Clang.
SimdLevel simd_level();

const char* simd_level_name(SimdLevel level);

}  // namespace rcdem

// A kernel's lanes are written once, as an always-inlined function, and wrapped three times: as
// is, with RCDEM_SIMD_TARGET_AVX2 and with RCDEM_SIMD_TARGET_AVX512, so that each wrapper compiles
// them for its instruction set; the kernel calls the wrapper simd_level() names.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define RCDEM_SIMD_TARGET_AVX2 __attribute__((target("avx2")))
#define RCDEM_SIMD_TARGET_AVX512 __attribute__((target("avx512f")))
#define RCDEM_SIMD_MULTIVERSION 1
#else
#define RCDEM_SIMD_MULTIVERSION 0
#endif
