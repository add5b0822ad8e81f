#pragma once
// Child processes without a shell: an argument vector handed to posix_spawn, so no path or name
// is ever parsed as shell code; stdout and stderr into a log file; the child's death by a signal
// reported as such, so that the caller can pass the user's Ctrl-C on instead of swallowing it.
#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace rcdem {

struct ChildStatus {
  bool exited = false;  // exited normally, with `code`
  int code = 0;
  int signal = 0;  // killed by this signal (exited false)
  bool ok() const { return exited && code == 0; }
  std::string describe() const;  // "exit status 2", "killed by SIGINT"
};

struct SpawnOptions {
  std::filesystem::path log;          // stdout and stderr (empty: /dev/null)
  bool append_log = false;            // append instead of truncating
  std::vector<std::string> env_set;   // NAME=VALUE entries replacing the inherited ones
  bool stop_with_parent = false;      // RCDEM_PARENT_PID set: an rcdem child stops when we die
};

// Starts `exe` with `args` (args[0] is the name the child sees). Throws Error when it cannot.
pid_t spawn_child(const std::filesystem::path& exe, const std::vector<std::string>& args,
                  const SpawnOptions& options);

// Waits for `pid`, through EINTR.
ChildStatus wait_child(pid_t pid);

// The last message in a child's log: its last non-empty line, and of a line a terminal's progress
// display rewrote with carriage returns, the text after the last one; "no output (see LOG)" when
// there is none.
std::string last_log_line(const std::filesystem::path& log);

// A status from waitpid's.
ChildStatus child_status(int wait_status);

// For an rcdem started by another rcdem (RCDEM_PARENT_PID in its environment): asks the kernel to
// send SIGTERM when that parent dies (a SIGKILLed study does not leave its runs running), and
// sends it at once when the parent is already gone.
void stop_with_parent_process();

// If the child was killed by SIGINT, SIGTERM or SIGHUP, the user asked to stop (a terminal's ^C
// reaches the whole process group): this process ends by the same signal.
void pass_on_interrupt(const ChildStatus& status);

// A file of rcdem's own (`relative` to its data: tools/..., examples/...): beside the installed
// binary (PREFIX/share/rcdem/...), else in the source tree it was built from; never the working
// directory. Empty when neither has it.
std::filesystem::path own_file(const std::filesystem::path& relative);

// One of rcdem's tools (plotting and report scripts): own_file("tools/" + name), a regular file.
std::filesystem::path own_tool(const std::string& name);

}  // namespace rcdem
