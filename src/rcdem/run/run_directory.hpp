#pragma once
// The output directory of a command: created if missing, never overwritten without --force, never
// shared with another live rcdem, never left holding two runs' files.
#include <filesystem>
#include <optional>
#include <vector>

#include "rcdem/run/run_manifest.hpp"

namespace rcdem::io {

// Creates `dir` (and parents). Refuses a path that is not a directory, or a directory that cannot
// be written, with a message naming it. Returns whether it created the directory. For a study's
// directory, which is resumed, not replaced (its lock: RunLock).
bool prepare_output_directory(const std::filesystem::path& dir);

// The directory a command (generate, run, calibrate) writes its results into, held for the
// command's lifetime:
//  * created if missing; its run.lock taken, so that no other rcdem works in it meanwhile (a
//    live run's directory is refused even with --force);
//  * a non-empty directory is refused unless `force`; with it, the earlier results are moved
//    aside into DIR/.rcdem-replaced first;
//  * commit() once the new results have started cleanly (a run past its set-up, a generation
//    written): the earlier results are deleted;
//  * destroyed uncommitted (the command failed or was refused): its new files are removed and
//    the earlier results put back, so a failure never leaves two runs' files side by side.
// A command killed between the two leaves DIR/.rcdem-replaced; the next command in DIR restores
// it first (the files beside it are the killed command's). DIR/run.log, which a study opens for
// the run it starts in DIR, is left where it is.
class OutputDirectory {
 public:
  OutputDirectory(std::filesystem::path dir, bool force);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  void commit();
  const std::filesystem::path& path() const { return dir_; }

  static constexpr const char* kReplacedName = ".rcdem-replaced";

 private:
  void restore() noexcept;

  std::filesystem::path dir_;
  bool created_ = false;
  bool committed_ = false;
  bool moved_aside_ = false;
  std::optional<RunLock> lock_;
};

}  // namespace rcdem::io
