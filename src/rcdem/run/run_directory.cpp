#include "rcdem/run/run_directory.hpp"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <set>

#include "rcdem/core/build_info.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/io/atomic_file.hpp"

namespace rcdem::io {

namespace fs = std::filesystem;

namespace {

bool create_or_check(const fs::path& dir) {
  std::error_code ec;
  bool created = false;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec))
      fail("output path '{}' exists and is not a directory", dir.string());
  } else {
    fs::create_directories(dir, ec);
    if (ec) fail("cannot create output directory '{}': {}", dir.string(), ec.message());
    created = true;
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    fail("output directory '{}' is not writable", dir.string());
  return created;
}

const std::string kDeleting = std::string(OutputDirectory::kReplacedName) + ".delete";
constexpr const char* kJournal = ".rcdem-journal";

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }
bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The entries of `dir` a command replaces: everything but the lock, the mark, the moved-aside
// results and run.log (the log a study opens for the run it starts in DIR, before that run starts).
std::vector<fs::path> results_in(const fs::path& dir) noexcept {
  std::vector<fs::path> entries;
  std::error_code ec;
  for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name != "run.lock" && name != "run.log" && name != OutputDirectory::kReplacedName &&
        name != kDeleting && name != OutputDirectory::kMarkName)
      entries.push_back(it->path());
  }
  std::sort(entries.begin(), entries.end());
  return entries;
}

std::set<std::string> names_in(const fs::path& dir, bool* readable = nullptr) {
  std::set<std::string> names;
  std::error_code ec;
  for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator();
       it.increment(ec))
    if (it->path().filename() != kJournal) names.insert(it->path().filename().string());
  if (readable) *readable = !ec;
  return names;
}

bool json_object_with(const fs::path& file, std::initializer_list<const char*> keys) {
  const auto j = nlohmann::json::parse(read_text(file), nullptr, false);
  if (j.is_discarded() || !j.is_object()) return false;
  for (const char* k : keys)
    if (!j.contains(k)) return false;
  return true;
}

// rcdem's mark, or the results of an rcdem older than the mark: a run's manifest.json, a
// generation's summary.json, a calibration's calibration.json.
bool bears_mark(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_regular_file(fs::symlink_status(dir / OutputDirectory::kMarkName, ec))) return true;
  return json_object_with(dir / "manifest.json", {"manifest_version", "rcdem_version"}) ||
         json_object_with(dir / "summary.json", {"particles", "contacts", "local_points"}) ||
         json_object_with(dir / "calibration.json", {"E", "nu", "sigma_c", "sigma_t"});
}

void write_mark(const fs::path& dir) {
  write_file_atomically(
      dir / OutputDirectory::kMarkName,
      fmt::format("This directory holds results written by rcdem {} ({}).\n"
                  "`--force` replaces only the entries rcdem writes, and only in a directory that "
                  "bears this file.\n",
                  build_version(), build_git_hash()));
}

std::string list_names(const std::vector<fs::path>& entries) {
  std::string s;
  for (std::size_t k = 0; k < entries.size() && k < 5; ++k)
    s += (k ? ", " : "") + ("'" + entries[k].filename().string() + "'");
  if (entries.size() > 5) s += fmt::format(" and {} more", entries.size() - 5);
  return s;
}

// Whether `input` is `entry` or lies inside it.
bool lies_in(const fs::path& input, const fs::path& entry) {
  std::error_code ec;
  const fs::path a = fs::weakly_canonical(input, ec), b = fs::weakly_canonical(entry, ec);
  auto ai = a.begin();
  for (auto bi = b.begin(); bi != b.end(); ++bi, ++ai)
    if (ai == a.end() || *ai != *bi) return false;
  return true;
}

}  // namespace

bool is_output_name(const std::string& name) {
  static const std::set<std::string> exact = {
      "scenario.toml",   "manifest.json",        "history.csv",        "summary.json",
      "broken_points.csv", "particles_initial.vtu", "particles.vtu",    "facets.vtu",
      "snapshots",       "particles.pvd",        "facets.pvd",         "bars.pvd",
      "load_displacement.png", "plot.log",       "calibration.json",   "calibrated_contact.toml",
      "figure7.png",     "compression",          "tension",            "final",
      "manifest.json.damaged"};
  if (name.find('\n') != std::string::npos) return false;
  if (exact.count(name)) return true;
  if (starts_with(name, "checkpoint_") &&
      (name.find(".h5") != std::string::npos || name.find(".rcp") != std::string::npos))
    return true;
  if (starts_with(name, "curve_") && ends_with(name, ".csv")) return true;
  if (starts_with(name, "iteration_")) return true;
  // An atomic write's temporary (NAME.tmp.PID) of one of the above.
  const auto tmp = name.find(".tmp.");
  return tmp != std::string::npos && tmp > 0 && is_output_name(name.substr(0, tmp));
}

bool prepare_output_directory(const fs::path& dir) { return create_or_check(dir); }

bool restore_replaced_results(const fs::path& dir) noexcept {
  std::error_code ec;
  const fs::path aside = dir / OutputDirectory::kReplacedName;
  if (!fs::is_directory(fs::symlink_status(aside, ec))) return false;
  bool readable = true;
  const std::set<std::string> moved = names_in(aside, &readable);
  if (!readable) return false;
  // The journal lists the earlier results before any is moved: an entry it names that is not
  // aside was never moved, and is kept. Without one (an older rcdem's), only the new entries
  // whose earlier versions are aside are removed.
  std::set<std::string> journal;
  std::ifstream in(aside / kJournal);
  const bool has_journal = static_cast<bool>(in);
  for (std::string line; std::getline(in, line);) journal.insert(line);
  for (const auto& p : results_in(dir)) {
    const std::string name = p.filename().string();
    const bool newer = moved.count(name) || (has_journal && !journal.count(name));
    if (newer && is_output_name(name)) fs::remove_all(p, ec);
  }
  for (const auto& name : moved) fs::rename(aside / name, dir / name, ec);
  fs::remove(aside / kJournal, ec);
  fs::remove(aside, ec);  // only once empty: whatever could not be moved back stays there
  return true;
}

OutputDirectory::OutputDirectory(fs::path dir, bool force, const std::vector<fs::path>& inputs)
    : dir_(std::move(dir)) {
  created_ = create_or_check(dir_);
  try {
    lock_.emplace(dir_, true);
    std::error_code ec;
    fs::remove_all(dir_ / kDeleting, ec);  // a commit that was killed while deleting
    restore_replaced_results(dir_);        // a command killed before its commit
    const std::vector<fs::path> earlier = results_in(dir_);
    if (!earlier.empty()) {
      if (!force)
        fail("output directory '{}' is not empty; use --force to overwrite its results",
             dir_.string());
      replace_earlier(earlier, inputs);
    }
    if (!fs::exists(dir_ / kMarkName, ec)) {
      write_mark(dir_);
      wrote_mark_ = true;
    }
  } catch (...) {
    if (moved_aside_) restore_replaced_results(dir_);
    moved_aside_ = false;
    lock_.reset();
    std::error_code ec;
    if (wrote_mark_) fs::remove(dir_ / kMarkName, ec);
    if (created_ && fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
    throw;
  }
}

// --force: checks that every earlier entry is rcdem's and none is an input, writes the journal,
// then moves them aside.
void OutputDirectory::replace_earlier(const std::vector<fs::path>& earlier,
                                      const std::vector<fs::path>& inputs) {
  if (!bears_mark(dir_))
    fail("output directory '{}' holds {}, but no results of rcdem (no {}): --force replaces only "
         "what rcdem wrote; choose a new or empty directory",
         dir_.string(), list_names(earlier), kMarkName);
  std::vector<fs::path> foreign;
  for (const auto& p : earlier)
    if (!is_output_name(p.filename().string())) foreign.push_back(p);
  if (!foreign.empty())
    fail("output directory '{}' holds {}, which rcdem did not write: --force replaces only rcdem's "
         "results; move them elsewhere or choose another directory",
         dir_.string(), list_names(foreign));
  for (const auto& input : inputs)
    for (const auto& p : earlier)
      if (lies_in(input, p))
        fail("'{}' is among the results --force would replace in '{}'; copy it out of the "
             "directory first",
             input.string(), dir_.string());
  std::error_code ec;
  fs::create_directory(dir_ / kReplacedName, ec);
  if (ec)
    fail("output directory '{}': cannot set its earlier results aside: {}", dir_.string(),
         ec.message());
  moved_aside_ = true;
  std::string journal;
  for (const auto& p : earlier) journal += p.filename().string() + "\n";
  write_file_atomically(dir_ / kReplacedName / kJournal, journal);
  for (const auto& p : earlier) {
    fs::rename(p, dir_ / kReplacedName / p.filename(), ec);
    if (ec)
      fail("output directory '{}': cannot set '{}' aside: {}; nothing was deleted", dir_.string(),
           p.filename().string(), ec.message());
  }
}

void OutputDirectory::commit() {
  if (committed_) return;
  committed_ = true;
  if (!moved_aside_) return;
  std::error_code ec;
  // Renamed first, so that a kill during the deletion cannot be mistaken for an uncommitted
  // replacement by the next command.
  fs::rename(dir_ / kReplacedName, dir_ / kDeleting, ec);
  if (!ec) fs::remove_all(dir_ / kDeleting, ec);
  moved_aside_ = false;
}

OutputDirectory::~OutputDirectory() {
  std::error_code ec;
  if (!committed_) {
    if (moved_aside_) {
      restore_replaced_results(dir_);
    } else {
      // Nothing was replaced: every result entry is this command's.
      for (const auto& p : results_in(dir_))
        if (is_output_name(p.filename().string())) fs::remove_all(p, ec);
    }
    if (wrote_mark_) fs::remove(dir_ / kMarkName, ec);
  }
  lock_.reset();
  if (created_ && fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
}

}  // namespace rcdem::io
