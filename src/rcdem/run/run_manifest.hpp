#pragma once
// The run directory's bookkeeping (docs/checkpoint.md): one rcdem at a time (run.lock), the
// manifest (manifest.json), the hash of the scenario's inputs a checkpoint must match.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace rcdem::io {

// flock on DIR/run.lock while a command works in DIR (released by the kernel however the process
// ends): a second rcdem in a live run's or study's directory (--resume, --force, generate, a
// second study) is refused instead of mixing files. Unlinked when released.
class RunLock {
 public:
  RunLock(const std::filesystem::path& dir, bool on);
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

// DIR/manifest.json: the scenario as run, the rcdem that ran it, threads, times, exit state and
// one entry per session (start, and each --resume). Rewritten atomically at the start, at every
// checkpoint and at the end.
class Manifest {
 public:
  Manifest(std::filesystem::path dir, bool on);
  nlohmann::ordered_json& json() { return j_; }
  nlohmann::ordered_json& session() { return j_["sessions"].back(); }
  // Reads DIR/manifest.json; a session still "running" there ended without a word: "killed".
  void load_existing();
  void write() const;
  void write_quietly() const noexcept;

 private:
  std::filesystem::path path_;
  bool on_;
  nlohmann::ordered_json j_ = nlohmann::ordered_json::object();
};

// The scenario's inputs: its text and the fragments it includes (resolved from `file`, where the
// scenario lives), each with its FNV-1a hash, and the hash of all together, which a checkpoint
// must match.
struct Inputs {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  std::uint64_t hash = 0;
};
Inputs scenario_inputs(const std::string& text, const std::filesystem::path& file);

std::string iso_now();  // UTC, ISO 8601
std::string read_text(const std::filesystem::path& p);            // "" if unreadable
void remove_stale_temporaries(const std::filesystem::path& dir);  // *.tmp.* of DIR, DIR/snapshots

}  // namespace rcdem::io
