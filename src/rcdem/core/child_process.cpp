#include "rcdem/core/child_process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "rcdem/core/error.hpp"
#include "rcdem/core/stop_signals.hpp"

extern char** environ;

namespace rcdem {

namespace fs = std::filesystem;

std::string ChildStatus::describe() const {
  if (exited) return fmt::format("exit status {}", code);
  const char* name = ::sigabbrev_np(signal);
  return name ? fmt::format("killed by SIG{}", name) : fmt::format("killed by signal {}", signal);
}

namespace {

std::vector<std::string> child_environment(const SpawnOptions& o) {
  std::vector<std::string> env;
  const auto overridden = [&](const char* entry) {
    for (const auto& s : o.env_set) {
      const auto eq = s.find('=');
      if (std::strncmp(entry, s.c_str(), eq + 1) == 0) return true;
    }
    return std::strncmp(entry, "RCDEM_PARENT_PID=", 17) == 0;
  };
  for (char** e = environ; *e; ++e)
    if (!overridden(*e)) env.emplace_back(*e);
  env.insert(env.end(), o.env_set.begin(), o.env_set.end());
  if (o.stop_with_parent) env.push_back(fmt::format("RCDEM_PARENT_PID={}", ::getpid()));
  return env;
}

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> p;
  for (auto& s : strings) p.push_back(s.data());
  p.push_back(nullptr);
  return p;
}

}  // namespace

pid_t spawn_child(const fs::path& exe, const std::vector<std::string>& args,
                  const SpawnOptions& o) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  const std::string log = o.log.empty() ? std::string("/dev/null") : o.log.string();
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | (o.append_log ? O_APPEND : O_TRUNC), 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  // The child gets the default dispositions whatever this process set (a study's handlers).
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t defaults, none;
  sigemptyset(&defaults);
  for (const int sig : kStopSignals) sigaddset(&defaults, sig);
  sigaddset(&defaults, SIGXFSZ);  // ignored by rcdem (main.cpp), not by its tools
  sigaddset(&defaults, SIGPIPE);
  sigemptyset(&none);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
  std::vector<std::string> argv_store = args, env_store = child_environment(o);
  std::vector<char*> argv = pointers(argv_store), envp = pointers(env_store);
  pid_t pid = 0;
  const int err = ::posix_spawn(&pid, exe.c_str(), &actions, &attr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (err != 0) fail("cannot start '{}': {}", exe.string(), std::strerror(err));
  return pid;
}

ChildStatus child_status(int wait_status) {
  ChildStatus s;
  if (WIFEXITED(wait_status)) {
    s.exited = true;
    s.code = WEXITSTATUS(wait_status);
  } else if (WIFSIGNALED(wait_status)) {
    s.signal = WTERMSIG(wait_status);
  }
  return s;
}

ChildStatus wait_child(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) fail("waiting for process {}: {}", pid, std::strerror(errno));
  return child_status(status);
}

std::string last_log_line(const fs::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line)) {
    const auto cr = line.find_last_of('\r');
    if (cr != std::string::npos) line = line.substr(cr + 1);
    if (line.find_first_not_of(" \t") != std::string::npos) last = line;
  }
  return last.empty() ? "no output (see " + log.string() + ")" : last;
}

void stop_with_parent_process() {
  const char* parent = std::getenv("RCDEM_PARENT_PID");
  if (!parent) return;
  char* end = nullptr;
  const long pid = std::strtol(parent, &end, 10);
  if (end == parent || *end != '\0' || pid <= 1) return;
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (::getppid() != static_cast<pid_t>(pid)) ::raise(SIGTERM);  // it died before prctl
}

void pass_on_interrupt(const ChildStatus& status) {
  if (status.exited || !is_stop_signal(status.signal)) return;
  std::signal(status.signal, SIG_DFL);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, status.signal);
  ::sigprocmask(SIG_UNBLOCK, &set, nullptr);
  std::raise(status.signal);
}

fs::path own_file(const fs::path& relative) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  std::vector<fs::path> roots;
  if (!ec) roots.push_back(exe.parent_path().parent_path() / "share" / "rcdem");
  roots.push_back(fs::path(RCDEM_SOURCE_DIR));
  for (const auto& root : roots)
    if (fs::exists(root / relative, ec)) return (root / relative).lexically_normal();
  return {};
}

fs::path own_tool(const std::string& name) {
  const fs::path p = own_file(fs::path("tools") / name);
  std::error_code ec;
  return fs::is_regular_file(p, ec) ? p : fs::path();
}

}  // namespace rcdem
