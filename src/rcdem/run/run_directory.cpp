#include "rcdem/run/run_directory.hpp"

#include <unistd.h>

#include "rcdem/core/error.hpp"

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

// The entries of `dir` that are results: everything but the lock, the moved-aside results and
// run.log (the log a study opens for the run it starts in DIR, before that run starts).
std::vector<fs::path> results_in(const fs::path& dir) noexcept {
  std::vector<fs::path> entries;
  std::error_code ec;
  for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name != "run.lock" && name != "run.log" && name != OutputDirectory::kReplacedName &&
        name != kDeleting)
      entries.push_back(it->path());
  }
  return entries;
}

}  // namespace

bool prepare_output_directory(const fs::path& dir) { return create_or_check(dir); }

OutputDirectory::OutputDirectory(fs::path dir, bool force) : dir_(std::move(dir)) {
  created_ = create_or_check(dir_);
  try {
    lock_.emplace(dir_, true);
    std::error_code ec;
    fs::remove_all(dir_ / kDeleting, ec);  // a commit that was killed while deleting
    if (fs::exists(dir_ / kReplacedName, ec)) {
      moved_aside_ = true;  // a command killed before its commit: undo what it did
      restore();
    }
    const std::vector<fs::path> earlier = results_in(dir_);
    if (earlier.empty()) return;
    if (!force)
      fail("output directory '{}' is not empty; use --force to overwrite its results",
           dir_.string());
    fs::create_directory(dir_ / kReplacedName, ec);
    if (ec)
      fail("output directory '{}': cannot set its earlier results aside: {}", dir_.string(),
           ec.message());
    moved_aside_ = true;
    for (const auto& p : earlier) {
      fs::rename(p, dir_ / kReplacedName / p.filename(), ec);
      if (ec)
        fail("output directory '{}': cannot set '{}' aside: {}", dir_.string(),
             p.filename().string(), ec.message());
    }
  } catch (...) {
    if (moved_aside_) restore();
    lock_.reset();
    std::error_code ec;
    if (created_ && fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
    throw;
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

void OutputDirectory::restore() noexcept {
  std::error_code ec;
  for (const auto& p : results_in(dir_)) fs::remove_all(p, ec);
  const fs::path aside = dir_ / kReplacedName;
  std::vector<fs::path> earlier;
  for (auto it = fs::directory_iterator(aside, ec); !ec && it != fs::directory_iterator();
       it.increment(ec))
    earlier.push_back(it->path());
  for (const auto& p : earlier) fs::rename(p, dir_ / p.filename(), ec);
  fs::remove(aside, ec);  // only once empty: whatever could not be moved back stays there
  moved_aside_ = false;
}

OutputDirectory::~OutputDirectory() {
  if (!committed_) restore();
  lock_.reset();
  std::error_code ec;
  if (created_ && fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
}

}  // namespace rcdem::io
