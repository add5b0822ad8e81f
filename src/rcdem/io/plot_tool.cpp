#include "rcdem/io/plot_tool.hpp"

#include <fmt/format.h>

#include "rcdem/core/child_process.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"

namespace rcdem::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPython = "/usr/bin/python3";

// The tool's status, or an Error saying why it could not start.
ChildStatus run_tool(const std::string& script, const fs::path& dir, const fs::path& log) {
  const fs::path tool = own_tool(script);
  if (tool.empty())
    fail("rcdem's tool '{}' is neither installed beside the binary nor in its source tree {}",
         script, RCDEM_SOURCE_DIR);
  SpawnOptions o;
  o.log = log;
  const ChildStatus status = wait_child(
      spawn_child(kPython, {"python3", tool.string(), dir.string()}, o));
  pass_on_interrupt(status);
  return status;
}

}  // namespace

void run_plot_tool(const std::string& script, const fs::path& dir) {
  const fs::path log = dir / "plot.log";
  std::error_code ec;
  try {
    const ChildStatus status = run_tool(script, dir, log);
    if (status.ok()) {
      fs::remove(log, ec);
      return;
    }
    if (!Progress::quiet_default())
      fmt::print(stderr,
                 "rcdem: warning: plotting failed ({}: {}; see {}); the results are in the CSV "
                 "files\n",
                 status.describe(), last_log_line(log), log.string());
  } catch (const Error& e) {
    if (!Progress::quiet_default())
      fmt::print(stderr, "rcdem: warning: no plot: {}; the results are in the CSV files\n",
                 e.what());
  }
}

void run_report_tool(const std::string& script, const fs::path& dir) {
  const fs::path log = dir / "report.log";
  const ChildStatus status = run_tool(script, dir, log);
  if (!status.ok())
    fail("{}: the report failed ({}): {} (the whole output is in {})", dir.string(),
         status.describe(), last_log_line(log), log.string());
}

}  // namespace rcdem::io
