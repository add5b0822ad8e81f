// What a checkpoint costs: its size, the time to write it (HDF5, synced and renamed, as a run
// does) and to restore it, and for comparison the binary image's encoding alone and written as a
// file (the .rcp format's write), on a scenario's specimen after some steps.
//
// Usage: rcdem_checkpoint_bench SCENARIO.toml [STEPS=50] [ROUNDS=3] [DIR=/tmp]
//   Prints one line per round (write_s, restore_s, encode_s, binary_write_s) and a summary line
//   with the HDF5 file's bytes, the medians and its write rate in MB/s.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/io/atomic_file.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: rcdem_checkpoint_bench SCENARIO.toml [STEPS=50] [ROUNDS=3] "
                 "[DIR=/tmp]\n");
    return 1;
  }
  const long steps = argc > 2 ? std::atol(argv[2]) : 50;
  const int rounds = argc > 3 ? std::atoi(argv[3]) : 3;
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(argc > 4 ? argv[4] : "/tmp") /
                       ("rcdem_checkpoint_bench_" + std::to_string(::getpid()));
  rcdem::Progress::set_quiet_default(true);
  try {
    const rcdem::Scenario sc = rcdem::load_scenario(argv[1]);
    rcdem::Simulation sim(sc, rcdem::build_specimen(sc));
    for (long k = 0; k < steps; ++k) sim.step();
    fs::create_directories(dir);
    const rcdem::io::CheckpointParts parts{&sim};
    std::vector<double> write, restore, encode, binary;
    std::uintmax_t bytes = 0;
    for (int r = 0; r < rounds; ++r) {
      auto t0 = std::chrono::steady_clock::now();
      const fs::path file = rcdem::io::write_checkpoint(dir, parts, 0, 1);
      write.push_back(seconds_since(t0));
      bytes = fs::file_size(file);
      t0 = std::chrono::steady_clock::now();
      rcdem::io::restore_checkpoint(file, parts, 0);
      restore.push_back(seconds_since(t0));
      t0 = std::chrono::steady_clock::now();
      const std::string image = rcdem::io::encode_checkpoint(parts, 0);
      encode.push_back(seconds_since(t0));
      // The binary image written as a file (the .rcp format's write, synced and renamed).
      rcdem::io::write_file_atomically(dir / "image.rcp", image);
      binary.push_back(seconds_since(t0));
      std::printf(
          "round %d write_s=%.4f restore_s=%.4f encode_s=%.4f binary_write_s=%.4f "
          "image_bytes=%zu\n",
          r, write.back(), restore.back(), encode.back(), binary.back(), image.size());
    }
    fs::remove_all(dir);
    std::printf(
        "bytes=%ju points=%lld write_s=%.4f restore_s=%.4f encode_s=%.4f binary_write_s=%.4f "
        "write_MB_per_s=%.0f\n",
        bytes, static_cast<long long>(sim.specimen().contacts.point_count()), median(write),
        median(restore), median(encode), median(binary),
        1e-6 * static_cast<double>(bytes) / median(write));
  } catch (const rcdem::Error& e) {
    std::fprintf(stderr, "rcdem_checkpoint_bench: %s\n", e.what());
    fs::remove_all(dir);
    return 1;
  }
  return 0;
}
