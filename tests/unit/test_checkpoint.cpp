// Checkpoints (issue 6, docs/checkpoint.md): a restored simulation continues bitwise as the
// original; damaged files (truncated, a flipped byte, another format) are rejected with a message
// naming the file and the reason, and the previous checkpoint is used; the state does not depend
// on the thread count.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "rcdem/config/scenario.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/run/crack_record.hpp"
#include "rcdem/run/run_output.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "small_scenarios.hpp"

using namespace rcdem;
namespace fs = std::filesystem;

namespace {

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const fs::path& p, const std::string& data) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << data;
}

// tests/regression/small_run.toml: bodies, a bar (cylinders, nodes, NL-A interface), two plates.
Scenario small_run() {
  return load_scenario(fs::path(RCDEM_SOURCE_DIR) / "tests/regression/small_run.toml");
}

// A bar pulled out of a small cube: the pulled-bar state; `loading` adds keys to [loading].
Scenario pull_out(const std::string& loading = "") {
  return parse_scenario(R"(
[specimen]
shape = "box"
size = [0.04, 0.04, 0.04]
[generation]
seed = 2
relaxation_iterations = 100
[bars.bar]
start = [0.0, 0.02, 0.02]
end = [0.035, 0.02, 0.02]
diameter = 0.008
cylinder_length = 0.00875
f_y = 1.0e9
interface = "NL-B"
pull_velocity = 1.0
pull_ramp_time = 2.0e-5
[plates.support]
face = "x-"
[stop]
displacement = 0.0005
[solver]
preset = "basic"
[loading]
control_bar = "bar"
)" + loading,
                        "pull_out.toml");
}

std::string encode(Simulation& sim, std::uint64_t hash = 7) {
  return io::encode_checkpoint(io::CheckpointParts{&sim}, hash);
}

class TempDir {
 public:
  TempDir() {
    static int count = 0;
    path_ = fs::temp_directory_path() /
            fmt::format("rcdem_ckpt_{}_{}_{}", ::getpid(),
                        ::testing::UnitTest::GetInstance()->current_test_info()->name(), count++);
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// "" when equal, else where two checkpoints first differ (never the bytes themselves).
std::string difference(const std::string& a, const std::string& b) {
  if (a == b) return "";
  std::size_t i = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
  return fmt::format("checkpoints of {} and {} bytes differ from byte {}", a.size(), b.size(), i);
}

// One bytewise CRC-32 step per byte: the reference the sliced version must equal.
std::uint32_t crc32_bytewise(const std::string& s) {
  std::uint32_t c = 0xFFFFFFFFU;
  for (unsigned char b : s) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c & 1U) ? 0xEDB88320U ^ (c >> 1) : c >> 1;
  }
  return ~c;
}

}  // namespace

TEST(Checkpoint, Crc32IsZlibs) {
  EXPECT_EQ(io::crc32("123456789", 9), 0xCBF43926U);  // the standard check value
  std::mt19937 rng(5);
  for (int len : {0, 1, 7, 8, 9, 63, 64, 1000, 4099}) {
    std::string s(static_cast<std::size_t>(len), '\0');
    for (char& c : s) c = static_cast<char>(rng() & 0xFFU);
    EXPECT_EQ(io::crc32(s.data(), s.size()), crc32_bytewise(s)) << len;
    // In two parts, continued.
    const std::size_t half = s.size() / 3;
    EXPECT_EQ(io::crc32(s.data() + half, s.size() - half, io::crc32(s.data(), half)),
              crc32_bytewise(s));
  }
  EXPECT_EQ(io::fnv1a64(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(io::fnv1a64("a"), 0xaf63dc4c8601ec8cULL);
}

// Saved after 300 steps and restored into a fresh simulation of the same scenario, the state
// equals the original bitwise, and stays equal over 300 more steps: nothing that a step uses is
// missing from the checkpoint.
TEST(Checkpoint, RestoredRunContinuesBitwise) {
  // The third with an adaptive loading rate whose factor has moved by step 300 (kinetic bound
  // out of reach, a doubling every 10 us): its controller's memory round-trips too.
  const Scenario adaptive = pull_out(
      "adaptive_rate = true\nkinetic_ratio = 0.99\nrate_doubling_time = 1e-5\n"
      "damage_work_ratio = 1e9\n");
  // The fourth with a bar across the pulled one, touching it and so tied (docs/model.md 14).
  const Scenario tied = pull_out(
      "[bars.cross]\nstart = [0.02, 0.004, 0.027]\nend = [0.02, 0.036, 0.027]\ndiameter = 0.006\n"
      "f_y = 5.0e8\ninterface = \"NL-B\"\n");
  for (const Scenario& sc : {small_run(), pull_out(), adaptive, tied}) {
    SCOPED_TRACE(sc.source.string() + (sc.bars.size() > 1 ? " (tied)" : ""));
    const Specimen specimen = build_specimen(sc);
    Simulation a(sc, specimen);
    for (int i = 0; i < 300; ++i) a.step();
    TempDir dir;
    const fs::path file = io::write_checkpoint(dir.path(), io::CheckpointParts{&a}, 7);
    EXPECT_EQ(file.filename(), "checkpoint_000000000300.h5");
    EXPECT_EQ(read_file(file).substr(0, 8), "RCDEMHDF");  // rcdem's header, then HDF5 from 512
    EXPECT_EQ(read_file(file).substr(512, 8), "\x89HDF\r\n\x1a\n");
    const std::string saved = io::checkpoint_image(file);
    EXPECT_EQ(difference(saved, encode(a)), "");

    Simulation b(sc, specimen);
    const io::CheckpointHeader h = io::restore_checkpoint(file, io::CheckpointParts{&b}, 7);
    EXPECT_EQ(h.step, 300);
    EXPECT_EQ(h.time, a.time());
    EXPECT_EQ(b.steps(), 300);
    EXPECT_EQ(difference(encode(b), saved), "");
    for (int i = 0; i < 300; ++i) {
      a.step();
      b.step();
    }
    EXPECT_EQ(difference(encode(a), encode(b)), "");
    EXPECT_EQ(a.time(), b.time());
    EXPECT_EQ(a.energy().external_work, b.energy().external_work);
    for (Index i = 0; i < a.bodies().size(); ++i)
      ASSERT_EQ(a.bodies().position[i], b.bodies().position[i]) << "body " << i;
    if (!a.pulled_bars().empty()) {
      EXPECT_EQ(a.pulled_bars()[0].displacement, b.pulled_bars()[0].displacement);
      EXPECT_GT(a.pulled_bars()[0].displacement, 0.0);
    }
    EXPECT_EQ(a.loading_rate_factor(), b.loading_rate_factor());
    if (sc.loading_rate.adaptive) EXPECT_GT(a.loading_rate_factor(), 1.0);
    // Something happened worth keeping: damage, node forces, plate reactions, a tie's force.
    EXPECT_GT(a.energy().damage + a.energy().friction, 0.0);
    if (sc.bars.size() > 1) {
      ASSERT_EQ(a.ties().size(), 1U);
      EXPECT_GT(a.ties().forces()[0].force_a.norm(), 0.0);
      EXPECT_EQ(a.ties().forces()[0].force_a, b.ties().forces()[0].force_a);
    }
  }
}

// The run loop's parts (history rows, crack record, snapshot series, loop scalars) round-trip too.
TEST(Checkpoint, RunPartsRoundTrip) {
  const Scenario sc = small_run();
  const Specimen specimen = build_specimen(sc);
  TempDir dir;
  Simulation a(sc, specimen);
  io::History ha(a, sc);
  io::SnapshotWriter wa(dir.path() / "a", false, true);
  io::CrackRecord ca(a);
  io::LoopState la;
  la.peak = 1.5;
  la.history_every = 30;
  la.snapshot_every = 1000;
  wa.write(a);
  for (int i = 1; i <= 1500; ++i) {
    a.step();
    if (i % 30 == 0) {
      ha.record(a);
      ca.update(a, 0.1 * i, 2.0 * i);
    }
  }
  wa.write(a);
  ASSERT_GT(ca.size(), 0U);
  const io::CheckpointParts pa{&a, &ha, &wa, &ca, &la};
  const fs::path file = io::write_checkpoint(dir.path(), pa, 11);

  Simulation b(sc, specimen);
  io::History hb(b, sc);
  io::SnapshotWriter wb(dir.path() / "b", false, true);
  io::CrackRecord cb(b);
  io::LoopState lb;
  const io::CheckpointParts pb{&b, &hb, &wb, &cb, &lb};
  io::restore_checkpoint(file, pb, 11);
  EXPECT_EQ(difference(io::encode_checkpoint(pb, 11), io::checkpoint_image(file)), "");
  EXPECT_EQ(hb.data(), ha.data());
  EXPECT_EQ(cb.size(), ca.size());
  EXPECT_EQ(cb.first_cracking(), ca.first_cracking());
  EXPECT_EQ(lb.peak, 1.5);
  EXPECT_EQ(lb.history_every, 30);
  // The snapshot series: the next .pvd lists the earlier files.
  a.step();
  b.step();
  wa.write(a);
  wb.write(b);
  EXPECT_EQ(read_file(dir.path() / "a" / "particles.pvd"),
            read_file(dir.path() / "b" / "particles.pvd"));
  EXPECT_NE(read_file(dir.path() / "b" / "particles.pvd").find("particles_000000000"),
            std::string::npos);
}

// Damaged or foreign files in the binary format (.rcp, still read): rejected before anything is
// changed, with the file and the reason.
TEST(Checkpoint, DamagedFilesAreRejectedWithTheReason) {
  const Scenario sc = small_run();
  const Specimen specimen = build_specimen(sc);
  Simulation a(sc, specimen);
  for (int i = 0; i < 50; ++i) a.step();
  TempDir dir;
  const fs::path good = io::write_checkpoint(dir.path(), io::CheckpointParts{&a}, 7);
  const std::string bytes = io::checkpoint_image(good);
  Simulation b(sc, specimen);
  const std::string fresh = encode(b);
  const auto restore_msg = [&](const std::string& data) {
    const fs::path f = dir.path() / "bad.rcp";
    write_file(f, data);
    const std::string m =
        message_of([&] { io::restore_checkpoint(f, io::CheckpointParts{&b}, 7); });
    EXPECT_NE(m.find("checkpoint '" + f.string() + "' rejected"), std::string::npos) << m;
    EXPECT_EQ(difference(encode(b), fresh), "") << "a rejected checkpoint changed the state";
    return m;
  };
  EXPECT_NE(restore_msg(bytes.substr(0, bytes.size() / 2)).find("truncated: "), std::string::npos);
  EXPECT_NE(restore_msg(bytes.substr(0, 10)).find("truncated"), std::string::npos);
  EXPECT_NE(restore_msg("").find("truncated"), std::string::npos);
  std::string flipped = bytes;
  flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x10);
  EXPECT_NE(restore_msg(flipped).find("checksum mismatch"), std::string::npos);
  std::string magic = bytes;
  magic[0] = 'X';
  EXPECT_NE(restore_msg(magic).find("not an rcdem checkpoint"), std::string::npos);
  std::string newer = bytes;
  newer[8] = static_cast<char>(io::kCheckpointVersion + 1);
  EXPECT_NE(restore_msg(newer).find(
                fmt::format("format version {} is newer", io::kCheckpointVersion + 1)),
            std::string::npos);
  std::string older = bytes;
  older[8] = static_cast<char>(io::kOldestReadableCheckpointVersion - 1);
  EXPECT_NE(restore_msg(older).find(fmt::format("format version {} is older",
                                                io::kOldestReadableCheckpointVersion - 1)),
            std::string::npos);
  EXPECT_NE(restore_msg(bytes + "x").find("data after the end"), std::string::npos);
  // Another scenario's inputs, another specimen.
  write_file(dir.path() / "ok.rcp", bytes);
  const std::string other = message_of(
      [&] { io::restore_checkpoint(dir.path() / "ok.rcp", io::CheckpointParts{&b}, 8); });
  EXPECT_NE(other.find("other scenario inputs"), std::string::npos) << other;
  Scenario sc2 = sc;
  sc2.generation.seed = 4;
  Simulation c(sc2, build_specimen(sc2));
  const std::string spec = message_of(
      [&] { io::restore_checkpoint(dir.path() / "ok.rcp", io::CheckpointParts{&c}, 7); });
  EXPECT_NE(spec.find("another specimen"), std::string::npos) << spec;
  // The intact file still restores.
  io::restore_checkpoint(dir.path() / "ok.rcp", io::CheckpointParts{&b}, 7);
  EXPECT_EQ(b.steps(), 50);
}

// The newest checkpoint damaged: the previous one is used, and the damaged one set aside; the
// last two are kept; none usable: one error naming each file and its reason.
TEST(Checkpoint, FallsBackToThePreviousCheckpoint) {
  const Scenario sc = small_run();
  const Specimen specimen = build_specimen(sc);
  Simulation a(sc, specimen);
  TempDir dir;
  std::string at200;
  for (int k = 1; k <= 3; ++k) {
    for (int i = 0; i < 100; ++i) a.step();
    io::write_checkpoint(dir.path(), io::CheckpointParts{&a}, 7);
    if (k == 2) at200 = encode(a);
  }
  const auto files = io::list_checkpoints(dir.path());
  ASSERT_EQ(files.size(), 2U) << "the last two are kept";
  EXPECT_EQ(files[0].step, 300);
  EXPECT_EQ(files[1].step, 200);
  // Truncate the newest, as a crash during a copy would.
  const std::string newest = read_file(files[0].path);
  write_file(files[0].path, newest.substr(0, newest.size() - 1000));
  Simulation b(sc, specimen);
  const io::RestoreReport rep =
      io::restore_latest_checkpoint(dir.path(), io::CheckpointParts{&b}, 7);
  EXPECT_EQ(rep.file, files[1].path);
  EXPECT_EQ(rep.header.step, 200);
  EXPECT_EQ(difference(encode(b), at200), "");
  ASSERT_EQ(rep.rejected.size(), 1U);
  EXPECT_NE(rep.rejected[0].find(files[0].path.string()), std::string::npos) << rep.rejected[0];
  EXPECT_NE(rep.rejected[0].find("truncated"), std::string::npos) << rep.rejected[0];
  EXPECT_TRUE(fs::exists(files[0].path.string() + ".rejected"));
  EXPECT_EQ(io::list_checkpoints(dir.path()).size(), 1U);

  // Both damaged.
  std::string last = read_file(files[1].path);
  last[last.size() / 2] = static_cast<char>(last[last.size() / 2] ^ 1);  // in a dataset
  write_file(files[1].path, last);
  const std::string none =
      message_of([&] { io::restore_latest_checkpoint(dir.path(), io::CheckpointParts{&b}, 7); });
  EXPECT_NE(none.find("no usable checkpoint"), std::string::npos) << none;
  EXPECT_NE(none.find(files[1].path.string()), std::string::npos) << none;
  EXPECT_NE(none.find("checksum mismatch"), std::string::npos) << none;
  TempDir empty;
  EXPECT_NE(message_of([&] {
              io::restore_latest_checkpoint(empty.path(), io::CheckpointParts{&b}, 7);
            }).find("no checkpoint in"),
            std::string::npos);
}

// A checkpoint that cannot be written (here: its name is taken by a directory, as a full disk or
// a read-only directory would refuse it) is an error naming it; the earlier ones are untouched.
TEST(Checkpoint, WriteFailureKeepsEarlierCheckpoints) {
  const Scenario sc = small_run();
  Simulation a(sc, build_specimen(sc));
  TempDir dir;
  for (int i = 0; i < 10; ++i) a.step();
  const fs::path first = io::write_checkpoint(dir.path(), io::CheckpointParts{&a}, 7);
  const std::string first_bytes = read_file(first);
  for (int i = 0; i < 10; ++i) a.step();
  const fs::path blocked = io::checkpoint_path(dir.path(), a.steps());
  fs::create_directories(blocked / "x");
  const std::string m =
      message_of([&] { io::write_checkpoint(dir.path(), io::CheckpointParts{&a}, 7); });
  EXPECT_NE(m.find("cannot write checkpoint '" + blocked.string() + "'"), std::string::npos) << m;
  EXPECT_NE(m.find("earlier checkpoints are kept"), std::string::npos) << m;
  EXPECT_EQ(difference(read_file(first), first_bytes), "");
  for (const auto& e : fs::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
  if (::geteuid() != 0) {  // root ignores permissions
    fs::remove_all(blocked);
    fs::permissions(dir.path(), fs::perms::owner_read | fs::perms::owner_exec);
    const std::string ro =
        message_of([&] { io::write_checkpoint(dir.path(), io::CheckpointParts{&a}, 7); });
    EXPECT_NE(ro.find("Permission denied"), std::string::npos) << ro;
    fs::permissions(dir.path(), fs::perms::owner_all);
    EXPECT_EQ(difference(read_file(first), first_bytes), "");
  }
}

// The same scenario at 1 and 2 threads: the whole state bitwise equal (the contact loop and the
// per-body gather take their parallel paths: 15,758 contacts, 2,517 bodies > 2,048).
TEST(Checkpoint, StateDoesNotDependOnThreadCount) {
#if !defined(_OPENMP)
  GTEST_SKIP() << "built without OpenMP";
#else
  std::string text = read_file(fs::path(RCDEM_SOURCE_DIR) / "tests/regression/small_run.toml");
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace("size = [0.05, 0.05, 0.05]", "size = [0.1, 0.1, 0.1]");
  replace("start = [0.005, 0.025, 0.025]", "start = [0.01, 0.05, 0.05]");
  replace("end = [0.045, 0.025, 0.025]", "end = [0.09, 0.05, 0.05]");
  replace("cylinder_length = 0.01", "cylinder_length = 0.02");
  replace("velocity = -0.5", "velocity = -2.0");
  replace("ramp_time = 5.0e-5", "ramp_time = 2.0e-5");
  // With the assembled critical step, whose operator runs in parallel: the same step too.
  replace("preset = \"basic\"",
          "preset = \"basic\"\ntime_step_estimate = \"assembled\"\ndt_safety = 0.8");
  const Scenario sc = parse_scenario(text, "cube100.toml");
  const Specimen specimen = build_specimen(sc);
  ASSERT_GT(specimen.contacts.contact_count(), 2048);
  const int threads = omp_get_max_threads();
  std::string state[2];
  Real damage[2] = {0, 0}, strain[2] = {0, 0}, dt[2] = {0, 0};
  for (int t = 0; t < 2; ++t) {
    omp_set_num_threads(t + 1);
    Simulation sim(sc, specimen);
    ASSERT_GT(sim.bodies().size(), 2048);
    ASSERT_TRUE(sim.critical_time_step().converged);
    dt[t] = sim.time_step();
    for (int i = 0; i < 250; ++i) sim.step();
    // Summed by blocks of contacts in parallel (some condensed, some from their points).
    strain[t] = sim.strain_energy();
    state[t] = encode(sim);
    damage[t] = sim.energy().damage;
  }
  omp_set_num_threads(threads);
  EXPECT_GT(damage[0], 0.0) << "the test should reach damage";
  EXPECT_EQ(damage[0], damage[1]);
  EXPECT_GT(strain[0], 0.0);
  EXPECT_EQ(strain[0], strain[1]);
  EXPECT_EQ(dt[0], dt[1]);
  EXPECT_EQ(difference(state[0], state[1]), "") << "1 and 2 threads differ";
#endif
}

// A checkpoint's sections: name -> (offset of its header's kind field, width, count).
struct SectionEntry {
  std::size_t at;
  std::uint32_t width;
  std::uint64_t count;
};
std::map<std::string, SectionEntry> section_table(const std::string& file) {
  const auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    std::memcpy(&v, file.data() + at, 4);
    return v;
  };
  std::map<std::string, SectionEntry> sections;
  std::size_t at = 64 + u32(60);
  for (std::uint32_t s = 0, n = u32(56); s < n; ++s) {
    const std::string name = file.substr(at + 4, u32(at));
    at += 4 + name.size();
    const std::uint32_t kind = u32(at), width = u32(at + 4);
    std::uint64_t count = 0;
    std::memcpy(&count, file.data() + at + 8, 8);
    sections[name] = {at, width, count};
    at += 16 + (kind == 1 ? 8 * width * count : count);
  }
  EXPECT_EQ(at + 4, file.size());
  return sections;
}

// The sections' widths are format version 8's (docs/checkpoint.md), now that each struct's
// serialize() names its columns and the width follows from their types: a column added or dropped
// without a new format version fails here, empty tables included (small_run pulls no bar).
// small_run.toml after 20 steps and a history row, with every part a run checkpoints.
struct SmallRunParts {
  Scenario sc = small_run();
  Simulation sim{sc, build_specimen(sc)};
  io::History history{sim, sc};
  TempDir dir;
  io::SnapshotWriter snapshots{dir.path(), false, true};
  io::CrackRecord cracks{sim};
  io::LoopState loop;
  SmallRunParts() {
    for (int i = 0; i < 20; ++i) sim.step();
    history.record(sim);
  }
  io::CheckpointParts parts() { return {&sim, &history, &snapshots, &cracks, &loop}; }
};

TEST(Checkpoint, SectionWidthsAreThoseOfTheFormatVersion) {
  ASSERT_EQ(io::kCheckpointVersion, 9U);
  SmallRunParts run;
  Simulation& sim = run.sim;
  io::History& history = run.history;
  const std::string file = io::encode_checkpoint(run.parts(), 3);
  auto sections = section_table(file);
  const std::map<std::string, std::uint32_t> v7 = {
      {"bodies", 22},
      {"bodies.step", 3},
      {"contacts", 17},
      {"contacts.points", 9},
      {"contacts.held", 35},
      {"contacts.held.entry", 10},
      {"contacts.held.clock", 2},
      {"interface.0", 17},
      {"interface.0.points", 9},
      {"nodes", 35},
      {"plates", 8},
      {"plate_contacts", 21},
      {"pulled_bars", 7},
      {"solver", 11},
      {"loading_rate", 3},
      {"history", static_cast<std::uint32_t>(history.columns().size())},
      {"snapshots.particles", 1},
      {"snapshots.facets", 1},
      {"snapshots.bars", 1},
      {"cracks", 7},
      {"run", 7}};
  for (const auto& [name, width] : v7) {
    ASSERT_TRUE(sections.count(name)) << name;
    EXPECT_EQ(sections[name].width, width) << name;
  }
  EXPECT_EQ(sections["pulled_bars"].count, 0U);  // an empty table keeps its width
  EXPECT_EQ(sections["bodies"].count, static_cast<std::uint64_t>(sim.bodies().size()));
}

// The same checkpoint in format 4, which held the peak twice in its "run" record.
std::string as_format4(const std::string& v5) {
  const SectionEntry run = section_table(v5).at("run");
  std::string v4 = v5;
  const std::size_t payload = run.at + 16;
  v4.insert(payload + 8, v5.substr(payload, 8));  // the peak again, after the peak
  const std::uint32_t version = 4, width = run.width + 1;
  std::memcpy(v4.data() + 8, &version, 4);
  std::memcpy(v4.data() + run.at + 4, &width, 4);
  const std::uint64_t size = v4.size();
  std::memcpy(v4.data() + 16, &size, 8);
  const std::uint32_t crc = io::crc32(v4.data(), v4.size() - 4);
  std::memcpy(v4.data() + v4.size() - 4, &crc, 4);
  return v4;
}

// A file of format 4 restores to the state a format-7 file of the same run holds (no contact is
// held in this run: formats 6 and 7 hold them).
TEST(Checkpoint, ReadsTheFormatBefore) {
  ASSERT_EQ(io::kOldestReadableCheckpointVersion, 4U);
  const Scenario sc = small_run();
  const Specimen specimen = build_specimen(sc);
  TempDir dir;
  Simulation a(sc, specimen);
  io::History ha(a, sc);
  io::LoopState la;
  for (int i = 1; i <= 300; ++i) a.step();
  ha.record(a);
  la.peak = 2.5;
  la.displacement_at_peak = 1e-4;
  la.history_every = 30;
  const std::string v5 = io::encode_checkpoint({&a, &ha, nullptr, nullptr, &la}, 5);
  write_file(dir.path() / "v4.rcp", as_format4(v5));
  Simulation b(sc, specimen);
  io::History hb(b, sc);
  io::LoopState lb;
  const io::CheckpointParts pb{&b, &hb, nullptr, nullptr, &lb};
  EXPECT_EQ(io::restore_checkpoint(dir.path() / "v4.rcp", pb, 5).version, 4U);
  EXPECT_EQ(lb.peak, 2.5);
  EXPECT_EQ(lb.displacement_at_peak, 1e-4);
  EXPECT_EQ(lb.history_every, 30);
  EXPECT_EQ(difference(io::encode_checkpoint(pb, 5), v5), "");
}

// Issue 46 (HDF5 checkpoints need it): every column of every section is named, with its SI unit,
// its words add up to the section's width, and docs/checkpoint.md's layout table lists it.
// RCDEM_PRINT_LAYOUT=1 prints that table's rows (the way to regenerate it).
void check_layout(const io::CheckpointParts& parts, std::set<std::string>& printed) {
  auto sections = section_table(io::encode_checkpoint(parts, 3));
  const std::vector<io::CheckpointColumn> layout = io::checkpoint_layout(parts);
  const std::string docs = read_file(fs::path(RCDEM_SOURCE_DIR) / "docs/checkpoint.md");
  const std::set<std::string> units = {"m",   "m^2", "m/s", "rad", "rad/s", "kg*m^2/s", "N",
                                       "N*m", "N/m", "J",   "s",   "1",     "-"};
  std::map<std::string, std::uint32_t> words;  // of the sections of words (not text, not rows)
  std::set<std::pair<std::string, std::string>> seen;
  for (const io::CheckpointColumn& c : layout) {
    ASSERT_TRUE(sections.count(c.section)) << c.section;
    EXPECT_TRUE(seen.insert({c.section, c.name}).second) << c.section << " " << c.name;
    const bool text = c.name == "text" || c.name == "bytes" || c.name == "row";
    if (!text) words[c.section] += c.words;
    EXPECT_FALSE(c.name.empty()) << c.section;
    if (!text)
      EXPECT_TRUE(units.count(c.unit)) << c.section << "." << c.name << ": '" << c.unit << "'";
    std::string section = c.section;
    if (section.rfind("interface.0", 0) == 0) section.replace(10, 1, "<bar>");
    const std::string width = c.name == "row" ? "one per history column"
                              : text          ? "–"
                                              : std::to_string(c.words);
    const std::string row = fmt::format("| `{}` | `{}` | {} | {} |", section, c.name,
                                        c.unit.empty() ? "–" : c.unit, width);
    if (std::getenv("RCDEM_PRINT_LAYOUT") && printed.insert(row).second) fmt::print("{}\n", row);
    EXPECT_NE(docs.find(row), std::string::npos) << "docs/checkpoint.md lacks the row " << row;
  }
  for (const auto& [name, w] : words) EXPECT_EQ(w, sections[name].width) << name;
}

TEST(Checkpoint, EveryColumnIsNamedWithItsUnitAndDocumented) {
  std::set<std::string> printed;
  {  // bodies, contacts, a bar's interface and nodes, plates, and the run loop's parts
    SmallRunParts run;
    check_layout(run.parts(), printed);
  }
  {  // a pulled bar
    const Scenario sc = pull_out();
    Simulation sim(sc, build_specimen(sc));
    sim.step();
    check_layout({&sim}, printed);
  }
  {  // a plate's loading program
    const Scenario sc = parse_scenario(test::small_box_text(2, "voronoi", R"(
[solver]
preset = "basic"
[plates.bottom]
face = "z-"
[plates.top]
face = "z+"
[plates.top.program.press]
kind = "displacement"
target = -0.0001
speed = 0.05
[loading]
control_plate = "top"
)"),
                                       "program_box.toml");
    Simulation sim(sc, build_specimen(sc));
    sim.step();
    check_layout({&sim}, printed);
  }
}
