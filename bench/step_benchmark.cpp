// Times Simulation::step() on a scenario's specimen and turns the time into throughput and memory
// bandwidth (issue: bench/ throughput and bandwidth, YADE side by side).
//
// Usage: rcdem_step_bench SCENARIO.toml STEPS [WARMUP=50] [REPEATS=1] [--checkpoint FILE]
//                         [--save-checkpoint DIR] [--threads N|auto,...] [--set KEY=VALUE ...]
//   --set: as rcdem run's (config/scenario_overrides.hpp), so that one binary times two settings
//   of a key (bench/ab_compare.py "BIN --set KEY=false" BIN: where the code lands in the binary
//   moves a step by a few percent, bench/RESULTS.md);
//   Generates the specimen (not timed); with --checkpoint, restores the state a run of that
//   scenario saved (run/checkpoint: a beam cracked half way through, say; the specimen must be the
//   same, the scenario's hash is not checked, so a copy of the scenario with other solver or
//   output keys serves); runs WARMUP steps (not timed; with --save-checkpoint, the state after
//   them is written to DIR/checkpoint_<step>.h5, so that a cracked state is made once and timed
//   at several thread counts; --threads times each count in turn, in this one process, each from
//   the state after the warm-up: one generation for all, and the same steps, which must end on
//   the same bits: end_strain_energy_J; `auto` is rcdem run's default: the count follows the
//   free cores up to the runtime's, core/thread_count_tuner.hpp), then times STEPS calls of
//   step() with steady_clock, REPEATS times back to back, and reports the fastest repetition (on a
//   shared machine the others carry its neighbours' load; bench/throughput.sh gives YADE the
//   same). Stop rules, history and snapshots are not involved (this is the step alone).
// Prints one line of key=value pairs (scenario, threads (a count, or auto with threads_mean,
// threads_last and threads_changes: the tuner's mean count over the steps, its last and how often
// it changed), bodies, contacts, local_points, steps,
// seconds, steps_per_s, particle_steps_per_s, contact_steps_per_s, local_point_steps_per_s,
// bytes_per_step, bytes_per_local_point, achieved_GBps, condensed_contacts: those evaluated from
// their sums at the last step, contact/elastic_condensation.hpp; held_contacts: damaged ones held
// to their sums, contact/held_contacts.hpp; cpu_seconds: the process's CPU
// time over the timed steps, all threads, idle spinning included: on a shared machine the steadier
// figure at 1 thread; both of the fastest repetition), repeat_seconds (every repetition's),
// strain_energy_seconds (Simulation::strain_energy() once after the steps, as a run's history row
// calls it: fastest of 3), scattered_lines and scattered_bytes (ByteCount::scattered_lines: the
// held contacts' sums and visited points, which bench/step_floor.py prices at random lines' cost)
// and a second line starting
// "# bytes:" with the breakdown of bytes_per_step (see bytes_per_step() below for the model and
// every term).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/config/scenario_overrides.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/huge_pages.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/core/thread_count_tuner.hpp"
#include "rcdem/core/thread_waiting.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"

namespace {

using rcdem::Index;
using rcdem::Quat;
using rcdem::Real;
using rcdem::Vec3;

// Bytes one step moves, COUNTED from the arrays Simulation::step() touches (a model, not a
// hardware counter). The model: every array a kernel of the step (contact loop, plate contacts,
// gather, integration, energy ledger) reads is counted once per kernel at its element size times
// its length, every array it writes likewise, an array both read and written twice. Body arrays
// gathered per contact (position, orientation, ... of A and B) are counted once per body per
// kernel, as if the repeated visits hit cache (10k bodies x ~0.6 kB fit in L2/L3); an array
// written in one kernel and read in a later one (force_b, energies) is counted in both. Arrays
// the step does not touch (distance0, facet_area, point_area, particles) are not counted. This is
// therefore the compulsory traffic: the least DRAM traffic a step could cause with these layouts.
//
// Per local point (concrete network), contact loop (contact_loop.hpp):
//   LocalPointRecord (local_point_records.hpp), two cache lines:
//     line 1: position at t = 0, LocalPointConstants, damage   read  64 (written back only when
//             the damage grows: not counted)
//     line 2: fn, fs1, fs2, un, us1, us2, un_max, us_max_sq    read + write  2 x 64
//                                                           = 192
// Per contact (concrete network):
//   contact loop: particle_a, particle_b   Index x 2 read     16
//                 point_begin              Index read          8
//                 normal, tangent          2 Vec3 read + write  96
//                 force_b, torque_b, torque_a  3 Vec3 write   72
//                 dissipated_damage, dissipated_friction  2 Real write  16
//   gather (ConcreteContacts::scatter, BodyContacts CSR):
//                 entry                    Index x 2 (one per side) read  16
//                 force_b, torque_b, torque_a  3 Vec3 read    72  (force_b is read by both
//                                          sides; counted once, the second visit is cached)
//   energy ledger: the 2 dissipations      2 Real read        16
//                                                           = 312
//   (a condensed contact: its sums and flags instead of its points, frame and dissipations)
// Per body (all bodies: concrete spheres and the bars' cylinders):
//   kinematics:   position Vec3 + orientation Quat read 56; rotation matrix (9 Real), position
//                 copy (Vec3) and pose (BodyPoses: 8 Real, one line) write 160
//   contact loop: pose read 64 (the condensed kernel); while some contacts go through their
//                 points also position copy, position0, angular_velocity 3 Vec3 and the rotation
//                 matrix read 144
//   gather:       begin, mid  2 Index read 16; force, torque  2 Vec3 write  48
//   integrate (a sphere, solver/sphere_update.cpp; the few cylinders are not counted apart):
//                 velocity, angular_velocity, position  3 Vec3 read + write 144; angular_momentum
//                 Vec3 write 24; orientation Quat read + write 64; force, torque, inertia  3 Vec3
//                 read 72; mass, radius  2 Real read 16; damping_work, kinetic  2 Real write 16;
//                 jumped  int64 write 8
//   instability check: jumped read 8
//   energy ledger: damping_work, kinetic  2 Real read 16
//                                                           = 712 (+ 144 with the point path)
// Per plate contact (solver/plates.cpp; one per boundary face under a plate's face):
//   evaluate: plate int r 4, particle Index r 8, point0 Vec3 r 24, constants r 32,
//             state LocalPointState r+w 176, force + torque Vec3 w 48, strain + friction Real w 16,
//             active uint8 r+w 2, body position + position0 Vec3 r 48 + orientation Quat r 32
//   reaction sum: plate 4, force 24, active 1;  gather: particle 8, force + torque 48, the body's
//   force + torque r+w 96;  energy ledger: strain + friction 16                 = 587
// Per interface contact (bars, SPEC 8; each one's particle A is a distinct concrete particle):
//   contact loop: particle_a/b 16, point_begin 8, anchor0 Vec3 r 24, normal + tangent r+w 96,
//                 force_b/torque_b/torque_a w 72, 2 dissipations w 16, body A position, position0,
//                 angular_velocity, orientation r 104 (B is a cylinder: few, cached)
//   gather (serial): particle_a/b 16, force_b/torque_b/torque_a r 72, A's force + torque r+w 96
//   energy ledger: 2 dissipations r 16                                           = 536
//   and per interface local point the same 200 as a concrete one.
// Per interaction node: node loop: NodeRef r, InteractionNode r, NodeState r+w, NodeForces w,
//   A's and B's position + orientation r 112; gather: NodeRef r, NodeForces r, A's and B's
//   force + torque r+w 192; energy: InteractionNode r, NodeState r, NodeForces.dissipated r 8.
struct ByteCount {
  double per_local_point = 0, per_contact = 0, per_condensed_contact = 0, per_held_contact = 0,
         per_body = 0, per_plate_contact = 0, per_interface_contact = 0, per_node = 0;
  double local_points = 0, contacts = 0, condensed_contacts = 0, held_contacts = 0,
         visited_points = 0, bodies = 0, plate_contacts = 0, interface_contacts = 0,
         interface_points = 0, nodes = 0;
  double points_total() const { return per_local_point * visited_points; }
  double contacts_total() const {
    return per_contact * (contacts - condensed_contacts - held_contacts) +
           per_condensed_contact * condensed_contacts + per_held_contact * held_contacts;
  }
  double bodies_total() const { return per_body * bodies; }
  double plates_total() const { return per_plate_contact * plate_contacts; }
  double interfaces_total() const {
    return per_interface_contact * interface_contacts + per_local_point * interface_points;
  }
  double nodes_total() const { return per_node * nodes; }
  // What no hardware prefetcher follows (bench/step_floor.py): the held contacts' sums, scattered
  // through their blocks, and the visited points' records, read where their contacts lie among
  // condensed ones; their lines, and the bytes of the count above they stand for. A block's sums
  // are a vector of HeldSums (malloc: 16-byte aligned), so a record starts at any 16-byte offset
  // in a line and touches every line it reaches from the worst one; a point's record is aligned
  // to lines (alignas(64)).
  static constexpr double kLine = 64, kMallocAlign = 16;
  static constexpr double kHeldSumLines =
      static_cast<int>((kLine - kMallocAlign + sizeof(rcdem::HeldSums) + kLine - 1) / kLine);
  static constexpr double kPointLines = sizeof(rcdem::LocalPointRecord) / kLine;
  double scattered_lines() const {
    return kHeldSumLines * held_contacts + kPointLines * (visited_points + interface_points);
  }
  double scattered_bytes() const {
    return static_cast<double>(sizeof(rcdem::HeldSums)) * held_contacts +
           static_cast<double>(sizeof(rcdem::LocalPointRecord)) *
               (visited_points + interface_points);
  }
  double total() const {
    return points_total() + contacts_total() + bodies_total() + plates_total() +
           interfaces_total() + nodes_total();
  }
};

ByteCount count_bytes(const rcdem::Simulation& sim) {
  constexpr double V = sizeof(Vec3), Q = sizeof(Quat), R = sizeof(Real), I = sizeof(Index);
  constexpr double LPS = sizeof(rcdem::LocalPointState);  // plate contacts' state
  constexpr double LPC = sizeof(rcdem::LocalPointConstants);
  constexpr double LINE = sizeof(rcdem::LocalPointRecord) / 2;  // one of a record's two lines
  ByteCount b;
  b.per_local_point = LINE + 2 * LINE;
  b.per_contact = (2 * I + I + 2 * 2 * V + 3 * V + 2 * R)  // contact loop
                  + (2 * I + 3 * V)                        // gather: CSR entries, force and torques
                  + 2 * R;                                 // energy ledger
  // A condensed contact (contact/elastic_condensation.hpp) reads its sums and two flags instead of
  // its points, and leaves its frame (normal, tangent: read + written) and its two dissipations
  // (exactly zero: not written, and its block's ledger sum reads only the visited contacts') alone.
  b.per_condensed_contact = b.per_contact - 2 * 2 * V - 2 * R - 2 * R +
                            rcdem::CondensedSums::kBytesPerContact + 2 * sizeof(std::uint8_t);
  // A held contact (contact/held_contacts.hpp) reads the same sums, its own (HeldSums) and its
  // frame (read + written), and writes its force and torques; its dissipations are zero.
  b.per_held_contact =
      b.per_condensed_contact + sizeof(rcdem::HeldSums) + 2 * 2 * V + sizeof(std::uint8_t);
  constexpr double J = sizeof(std::int64_t), P = rcdem::BodyPoses::kStride * R;
  const bool point_path = sim.condensed_contacts() < sim.specimen().contacts.contact_count();
  b.per_body = (V + Q + 9 * R + V + P)                                // kinematics
               + P + (point_path ? 3 * V + 9 * R : 0.0)               // contact loop
               + (2 * I + 2 * V)                                      // gather
               + (3 * 2 * V + V + 2 * Q + 3 * V + 2 * R + 2 * R + J)  // integrate
               + J                                                    // instability check
               + 2 * R;                                               // energy ledger
  b.per_plate_contact = (sizeof(int) + I + V + LPC + 2 * LPS + 2 * V + 2 * R +
                         2 * sizeof(std::uint8_t) + 2 * V + Q)      // evaluate
                        + (sizeof(int) + V + sizeof(std::uint8_t))  // reaction sum
                        + (I + 2 * V + 2 * 2 * V)                   // gather
                        + 2 * R;                                    // energy ledger
  b.per_interface_contact = (2 * I + I + V + 2 * 2 * V + 3 * V + 2 * R + 3 * V + Q)  // loop
                            + (2 * I + 3 * V + 2 * 2 * V)                            // gather
                            + 2 * R;                                                 // energy
  constexpr double NR = sizeof(rcdem::NodeRef), NC = sizeof(rcdem::InteractionNode),
                   NS = sizeof(rcdem::NodeState), NF = sizeof(rcdem::NodeForces);
  b.per_node = (NR + NC + 2 * NS + NF + 2 * (V + Q))  // node loop
               + (NR + NF + 2 * 2 * 2 * V)            // gather
               + (NC + NS + R);                       // energy ledger

  const rcdem::Specimen& sp = sim.specimen();
  b.local_points = static_cast<double>(sp.contacts.point_count());
  b.contacts = static_cast<double>(sp.contacts.contact_count());
  // As the last step left them (the count changes slowly over a run).
  b.condensed_contacts = static_cast<double>(sim.condensed_contacts());
  b.held_contacts = static_cast<double>(sim.held_contacts());
  b.visited_points = b.local_points - static_cast<double>(sim.condensed_points()) -
                     static_cast<double>(sim.held_points());
  b.bodies = static_cast<double>(sim.bodies().size());
  b.plate_contacts = static_cast<double>(sim.plate_contacts().size());
  for (const auto& ic : sp.interfaces) {
    b.interface_contacts += static_cast<double>(ic.net.contact_count());
    b.interface_points += static_cast<double>(ic.net.point_count());
  }
  b.nodes = static_cast<double>(sim.nodes().size());
  return b;
}

}  // namespace

// The bytes one step moves (see count_bytes above for every term).
double bytes_per_step(const rcdem::Simulation& sim) { return count_bytes(sim).total(); }

namespace {

struct BenchArgs {
  std::string path, checkpoint, save_dir;
  long steps = 0, warmup = 50, repeats = 1;
  std::vector<int> threads;            // --threads: each count (0: auto) timed from the same state
  std::vector<std::string> overrides;  // --set KEY=VALUE, in order
};

const char* const kUsage =
    "usage: rcdem_step_bench SCENARIO.toml STEPS [WARMUP=50] [REPEATS=1] [--checkpoint FILE] "
    "[--save-checkpoint DIR] [--threads N|auto,...] [--set KEY=VALUE ...]\n";

std::vector<int> parse_threads(const std::string& text) {
  std::vector<int> out;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, comma - at);
    std::size_t used = 0;
    const int t = item == "auto" ? 0 : std::stoi(item, &used);
    if (item != "auto" && (used != item.size() || t <= 0)) throw std::invalid_argument(text);
    out.push_back(t);
    at = comma + 1;
  }
  return out;
}

// Returns false (after printing why) on a malformed command line.
bool parse_args(int argc, char** argv, BenchArgs& a) {
  std::vector<std::string> pos;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string opt = argv[i];
      const bool takes_value = opt == "--checkpoint" || opt == "--save-checkpoint" ||
                               opt == "--threads" || opt == "--set";
      if (!takes_value) {
        pos.push_back(opt);
        continue;
      }
      if (i + 1 >= argc) {
        std::fprintf(stderr, "rcdem_step_bench: %s needs a value\n%s", opt.c_str(), kUsage);
        return false;
      }
      const std::string v = argv[++i];
      if (opt == "--checkpoint") a.checkpoint = v;
      if (opt == "--save-checkpoint") a.save_dir = v;
      if (opt == "--threads") a.threads = parse_threads(v);
      if (opt == "--set") a.overrides.push_back(v);
    }
    if (pos.size() < 2 || pos.size() > 4) {
      std::fprintf(stderr, "%s", kUsage);
      return false;
    }
    a.path = pos[0];
    a.steps = std::stol(pos[1]);
    if (pos.size() >= 3) a.warmup = std::stol(pos[2]);
    if (pos.size() >= 4) a.repeats = std::stol(pos[3]);
  } catch (const std::exception&) {
    a.steps = -1;
  }
  if (a.steps <= 0 || a.warmup < 0 || a.repeats <= 0) {
    std::fprintf(stderr,
                 "rcdem_step_bench: STEPS and REPEATS must be > 0, WARMUP >= 0 and --threads a "
                 "comma-separated list of counts > 0 (whole numbers) or auto\n");
    return false;
  }
  return true;
}

// Times STEPS steps REPEATS times from the simulation's present state at `threads` (0: auto, the
// runtime's count the most) and prints the result lines (see the file's head). `setup_s` is
// reported as given.
void time_and_report(rcdem::Simulation& sim, const BenchArgs& a, double setup_s, int threads) {
  double seconds = 0, cpu_seconds = 0;
  std::string repeat_seconds;
  rcdem::ThreadRecord used;
  for (long r = 0; r < a.repeats; ++r) {
    rcdem::StepThreads step_threads(threads);
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    for (long k = 0; k < a.steps; ++k) step_threads.step([&] { sim.step(); });
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    repeat_seconds += (r ? "," : "") + std::to_string(s);
    if (r == 0 || s < seconds) {
      seconds = s;
      cpu_seconds = cpu;
      used = step_threads.record();
    }
  }

  // The strain energy a history row of a run reads (not part of the step; before count_bytes,
  // which must see the last step's condensed contacts as the row does): fastest of 3.
  double strain_energy_s = 0, strain_energy = 0;
  for (int r = 0; r < 3; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    strain_energy = sim.strain_energy();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (r == 0 || s < strain_energy_s) strain_energy_s = s;
  }

  const ByteCount bc = count_bytes(sim);
  const double bytes = bytes_per_step(sim);
  const auto bodies = static_cast<double>(sim.bodies().size());
  const auto contacts = static_cast<double>(sim.specimen().contacts.contact_count());
  const auto points = static_cast<double>(sim.specimen().contacts.point_count());
  const double rate = static_cast<double>(a.steps) / seconds;
  std::printf(
      "scenario=%s threads=%s threads_mean=%.3f threads_last=%d threads_changes=%ld bodies=%.0f "
      "contacts=%.0f local_points=%.0f steps=%ld "
      "seconds=%.4f steps_per_s=%.3f particle_steps_per_s=%.4g contact_steps_per_s=%.4g "
      "local_point_steps_per_s=%.4g bytes_per_step=%.0f bytes_per_local_point=%.1f "
      "achieved_GBps=%.3f setup_seconds=%.2f condensed_contacts=%.0f held_contacts=%ld "
      "cpu_seconds=%.4f repeat_seconds=%s strain_energy_seconds=%.5f end_strain_energy_J=%.17g "
      "scattered_lines=%.0f scattered_bytes=%.0f\n",
      a.path.c_str(), used.tuned ? "auto" : std::to_string(used.max).c_str(), used.mean, used.last,
      static_cast<long>(used.changes), bodies, contacts, points, a.steps, seconds, rate,
      rate * bodies, rate * contacts, rate * points, bytes, bytes / points, bytes * rate * 1e-9,
      setup_s, bc.condensed_contacts, static_cast<long>(sim.held_contacts()), cpu_seconds,
      repeat_seconds.c_str(), strain_energy_s, strain_energy, bc.scattered_lines(),
      bc.scattered_bytes());
  std::printf(
      "# bytes: per_local_point=%.0f x %.0f visited = %.4g; per_contact=%.0f x %.0f + "
      "condensed %.0f x %.0f + held %.0f x %.0f = %.4g; "
      "per_body=%.0f x %.0f = %.4g; plates=%.0f x %.0f = %.4g; interfaces=%.0f x %.0f "
      "+ %.0f x %.0f points = %.4g; nodes=%.0f x %.0f = %.4g; total=%.4g\n",
      bc.per_local_point, bc.visited_points, bc.points_total(), bc.per_contact,
      bc.contacts - bc.condensed_contacts - bc.held_contacts, bc.per_condensed_contact,
      bc.condensed_contacts, bc.per_held_contact, bc.held_contacts, bc.contacts_total(),
      bc.per_body, bc.bodies, bc.bodies_total(), bc.per_plate_contact, bc.plate_contacts,
      bc.plates_total(), bc.per_interface_contact, bc.interface_contacts, bc.per_local_point,
      bc.interface_points, bc.interfaces_total(), bc.per_node, bc.nodes, bc.nodes_total(),
      bc.total());
  std::fflush(stdout);
}

// With --threads, every count starts from the state after the warm-up, saved once and restored
// before each, so the counts time the same steps and must end on the same bits.
void time_each_thread_count(rcdem::Simulation& sim, const BenchArgs& a, double setup_s) {
  namespace fs = std::filesystem;
  const bool own_dir = a.save_dir.empty();
  const fs::path dir =
      own_dir ? fs::temp_directory_path() / ("rcdem_step_bench_" + std::to_string(::getpid()))
              : fs::path(a.save_dir);
  fs::create_directories(dir);
  const fs::path state = rcdem::io::write_checkpoint(dir, rcdem::io::CheckpointParts{&sim}, 0);
  for (const int t : a.threads) {
    rcdem::io::restore_checkpoint(state, rcdem::io::CheckpointParts{&sim}, 0);
    time_and_report(sim, a, setup_s, t);
  }
  if (own_dir) fs::remove_all(dir);
}

}  // namespace

int main(int argc, char** argv) {
  rcdem::prefer_huge_pages(argv);          // as rcdem does (core/huge_pages.hpp)
  rcdem::prefer_passive_thread_waiting();  // as rcdem does (core/thread_waiting.hpp)
  BenchArgs a;
  if (!parse_args(argc, argv, a)) return 1;
  rcdem::Progress::set_quiet_default(true);  // no generation progress lines among the results
  try {
    const auto g0 = std::chrono::steady_clock::now();
    const rcdem::Scenario sc = rcdem::config::load_scenario_on_seed(a.path, {}, a.overrides);
    rcdem::Simulation sim(sc, rcdem::build_specimen(sc));
    if (!a.checkpoint.empty()) {
      // Only the simulation's sections are read; the specimen's fingerprint is still checked.
      const auto header = rcdem::io::inspect_checkpoint(a.checkpoint);
      rcdem::io::restore_checkpoint(a.checkpoint, rcdem::io::CheckpointParts{&sim},
                                    header.scenario_hash);
    }
    const double setup_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - g0).count();
    // Warm-up: caches, pages, branch history; a long one loads the specimen into cracking, so
    // that the timed steps see damaged contacts (the default 50 leaves every contact elastic).
    for (long k = 0; k < a.warmup; ++k) sim.step();
    if (!a.threads.empty()) {
      time_each_thread_count(sim, a, setup_s);
      return 0;
    }
    if (!a.save_dir.empty()) {
      std::filesystem::create_directories(a.save_dir);
      rcdem::io::write_checkpoint(a.save_dir, rcdem::io::CheckpointParts{&sim}, 0);
    }
    time_and_report(sim, a, setup_s, rcdem::runtime_thread_count());
  } catch (const rcdem::Error& e) {
    std::fprintf(stderr, "rcdem_step_bench: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rcdem_step_bench: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
