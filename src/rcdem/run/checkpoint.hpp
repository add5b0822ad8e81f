#pragma once
// Checkpoints of a run (issue 6; the format is documented in docs/checkpoint.md): the whole state
// that a step changes (bodies, every contact and local point, interfaces, nodes, plates and their
// contacts, pulled bars, time, step, energy) and the run loop's own state (peak, history rows,
// crack record, snapshot series). The state is encoded as a versioned little-endian binary image
// with a CRC-32 trailer (the format of .rcp files, still read) and written as HDF5
// (run/checkpoint_hdf5.hpp: the same sections as groups of named datasets with their units).
//
// The specimen (particles, network, constants) is not stored: it is regenerated from the scenario
// and its seed, and a fingerprint of it in the header must match. No random numbers are drawn
// during stepping, so there is no generator state to keep.
//
// Files are DIR/checkpoint_<step, 12 digits>.h5, written to a temporary name, synced and renamed;
// the last two are kept. Loading takes the newest one that passes every check and falls back to
// the older one, saying which file was rejected and why.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rcdem/core/archive.hpp"

namespace rcdem {
class Simulation;
}

namespace rcdem::io {

class History;
class SnapshotWriter;
class CrackRecord;

inline constexpr char kCheckpointMagic[9] = "RCDEMCKP";
// The version written, and the oldest read (docs/checkpoint.md: what changed between them).
inline constexpr std::uint32_t kCheckpointVersion = 9;
inline constexpr std::uint32_t kOldestReadableCheckpointVersion = 4;

// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320: the CRC of zlib, PNG and gzip), so that
// zlib.crc32 in Python checks a file. `crc` continues an earlier call.
std::uint32_t crc32(const void* data, std::size_t size, std::uint32_t crc = 0);
// FNV-1a, 64 bits: identity hashes (scenario inputs, specimen fingerprint), not error detection.
std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t h = 0xcbf29ce484222325ULL);
inline std::uint64_t fnv1a64(std::string_view s, std::uint64_t h = 0xcbf29ce484222325ULL) {
  return fnv1a64(s.data(), s.size(), h);
}

// A hash of what the regenerated specimen must equal: counts of bodies, contacts, points, plate
// contacts, nodes, interface contacts, and the bodies' reference positions, masses, inertias,
// the points' reference positions and constants, the plate contacts' points and constants.
std::uint64_t specimen_fingerprint(const Simulation& sim);

// The run loop's own scalars (run/run.cpp).
struct LoopState {
  double peak = 0.0;  // largest load so far: the peak load
  double displacement_at_peak = 0.0, kinetic_over_strain_at_peak = 0.0;
  double wall_seconds = 0.0;  // wall time of the sessions so far, up to this checkpoint
  double loop_seconds = 0.0;  // the part of it spent stepping
  std::int64_t history_every = 0, snapshot_every = 0;  // spacing (checked on restore)

  // The checkpoint's "run" record (core/archive.hpp). Format 4 held the peak twice.
  template <class Archive, class Self>
  static void serialize(Archive& ar, Self& l) {
    // The peak, then what format 4 held after it (its second copy), then the rest.
    const auto run = [&](auto... after_peak) {
      ar.record("run", named("peak", "N", l.peak), after_peak...,
                named("displacement_at_peak", "m", l.displacement_at_peak),
                named("kinetic_over_strain_at_peak", "1", l.kinetic_over_strain_at_peak),
                named("wall_seconds", "s", l.wall_seconds),
                named("loop_seconds", "s", l.loop_seconds),
                named("history_every", "-", l.history_every),
                named("snapshot_every", "-", l.snapshot_every));
    };
    if constexpr (Archive::loading) {
      if (ar.version() == 4) {
        double peak_again = 0.0;
        run(named("peak_again", "N", peak_again));
        return;
      }
    }
    run();
  }
};

// What a checkpoint holds: the simulation always; the run loop's parts where given.
struct CheckpointParts {
  Simulation* sim = nullptr;
  History* history = nullptr;
  SnapshotWriter* snapshots = nullptr;
  CrackRecord* cracks = nullptr;
  LoopState* loop = nullptr;
};

// The fixed part of the header.
struct CheckpointHeader {
  std::uint32_t version = 0;
  std::uint64_t file_size = 0;
  std::int64_t step = 0;
  double time = 0.0;
  std::uint64_t scenario_hash = 0;
  std::uint64_t specimen_fingerprint = 0;
  std::uint32_t sections = 0;
  std::string writer;  // "rcdem VERSION (GIT HASH)"
};

// One column of a checkpoint's section as written (docs/checkpoint.md): `name` the path of the
// names a serialize() gives it ("record.history.fs.t1"), its SI unit ("1": dimensionless; "-": a
// count, index or flag; empty for text and byte sections, and for the history's rows, whose
// header names their units), its width in 64-bit words, and whether they are reals.
struct CheckpointColumn {
  std::string section, name, unit;
  std::uint32_t words = 0;
  bool real = false;
};
// What encode_checkpoint would write for `parts`, column by column, in the file's order.
std::vector<CheckpointColumn> checkpoint_layout(const CheckpointParts& parts);

// The binary image (an .rcp file's bytes), in memory. `scenario_hash` identifies the scenario's
// inputs (run.cpp).
std::string encode_checkpoint(const CheckpointParts& parts, std::uint64_t scenario_hash);

// Checks a file's framing (size, magic, version, byte order, length, checksum) and section
// table; returns its header or throws rcdem::Error "checkpoint 'FILE' rejected: REASON". Either
// format: an HDF5 file is read into its binary image first.
CheckpointHeader inspect_checkpoint(const std::filesystem::path& file);

// A checkpoint file's binary image (an HDF5 file's converted back: what encode_checkpoint gave
// for the state it holds), its framing and checksum checked; throws as inspect_checkpoint.
std::string checkpoint_image(const std::filesystem::path& file);

// Restores `parts` from one file. Every check (framing, checksum, scenario hash, specimen
// fingerprint, every section's presence and size) passes before anything is changed; on failure
// throws rcdem::Error "checkpoint 'FILE' rejected: REASON" and leaves `parts` as they were.
CheckpointHeader restore_checkpoint(const std::filesystem::path& file, const CheckpointParts& parts,
                                    std::uint64_t scenario_hash);

// DIR/checkpoint_<step>.h5 (and .rcp, the binary format before), newest (highest step) first.
// Ignores temporary files.
struct CheckpointFile {
  std::filesystem::path path;
  std::int64_t step = 0;
};
std::vector<CheckpointFile> list_checkpoints(const std::filesystem::path& dir);
std::filesystem::path checkpoint_path(const std::filesystem::path& dir, std::int64_t step);

// Writes the checkpoint of `parts` into `dir` atomically (temporary file, fsync, rename, fsync of
// the directory), then removes all but the newest `keep` checkpoints and any temporary file an
// interrupted write left behind. On failure (disk full, directory not writable) throws
// rcdem::Error naming the file and the reason; the earlier checkpoints are untouched.
std::filesystem::path write_checkpoint(const std::filesystem::path& dir,
                                       const CheckpointParts& parts, std::uint64_t scenario_hash,
                                       int keep = 2);

// Restores from the newest usable checkpoint in `dir`, falling back to older ones. `rejected`
// receives one line per file passed over ("checkpoint 'FILE' rejected: REASON"). Throws
// rcdem::Error if none is usable (naming each file and its reason, or saying there is none).
struct RestoreReport {
  std::filesystem::path file;
  CheckpointHeader header;
  std::vector<std::string> rejected;
};
RestoreReport restore_latest_checkpoint(const std::filesystem::path& dir,
                                        const CheckpointParts& parts, std::uint64_t scenario_hash);

// Removes every checkpoint (and temporary checkpoint file) in `dir`.
void remove_checkpoints(const std::filesystem::path& dir);

// Friend of the classes whose private state a checkpoint holds (Simulation, History,
// SnapshotWriter, CrackRecord); defined in checkpoint.cpp only.
struct CheckpointAccess;

}  // namespace rcdem::io
