#pragma once
// The output directory of a command: created if missing, never overwritten without --force, never
// shared with another live rcdem, never left holding two runs' files, and never a place where
// rcdem deletes a file it did not write (docs/checkpoint.md, "What --force touches").
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rcdem/run/run_manifest.hpp"

namespace rcdem::io {

// Creates `dir` (and parents). Refuses a path that is not a directory, or a directory that cannot
// be written, with a message naming it. Returns whether it created the directory. For a study's
// directory, which is resumed, not replaced (its lock: RunLock).
bool prepare_output_directory(const std::filesystem::path& dir);

// Whether `name` is one of the entries rcdem's commands write into an output directory (results,
// snapshots, checkpoints, logs, their temporaries).
bool is_output_name(const std::string& name);

// The directory a command (generate, run, calibrate) writes its results into, held for the
// command's lifetime:
//  * created if missing; its run.lock taken, so that no other rcdem works in it meanwhile (a
//    live run's directory is refused even with --force);
//  * marked as rcdem's (DIR/.rcdem-outputs);
//  * a non-empty directory is refused unless `force`; with it, it is refused too unless it bears
//    rcdem's mark (or is an older rcdem's run directory) and every entry is one rcdem writes, and
//    unless none of `inputs` (the scenario being run) lies among them. The earlier results are
//    then moved aside into DIR/.rcdem-replaced, after a list of them is written there;
//  * commit() once the new results have started cleanly (a run past its set-up, a generation
//    written): the earlier results are deleted;
//  * destroyed uncommitted (the command failed or was refused): its new files are removed and
//    the earlier results put back, so a failure never leaves two runs' files side by side.
// A command killed between the two leaves DIR/.rcdem-replaced; the next command in DIR (or
// --resume) restores it first. DIR/run.log, which a study opens for the run it starts in DIR,
// is left where it is.
class OutputDirectory {
 public:
  OutputDirectory(std::filesystem::path dir, bool force,
                  const std::vector<std::filesystem::path>& inputs = {});
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  void commit();
  const std::filesystem::path& path() const { return dir_; }

  static constexpr const char* kReplacedName = ".rcdem-replaced";
  static constexpr const char* kMarkName = ".rcdem-outputs";

 private:
  void replace_earlier(const std::vector<std::filesystem::path>& earlier,
                       const std::vector<std::filesystem::path>& inputs);

  std::filesystem::path dir_;
  bool created_ = false;
  bool committed_ = false;
  bool moved_aside_ = false;
  bool wrote_mark_ = false;
  std::optional<RunLock> lock_;
};

// Puts back the earlier results of a --force that was killed before its new results started
// (DIR/.rcdem-replaced), removing what the killed command wrote. The caller holds DIR's lock.
// Returns whether there was anything to restore.
bool restore_replaced_results(const std::filesystem::path& dir) noexcept;

}  // namespace rcdem::io
