#include "rcdem/io/plot_tool.hpp"

#include <fmt/format.h>

#include <cstdlib>

#include "rcdem/core/progress.hpp"

namespace rcdem::io {

void run_plot_tool(const std::string& script, const std::filesystem::path& dir) {
  // From the repository root, or from the source tree the binary was built from.
  for (const std::string& path :
       {"tools/" + script, std::string(RCDEM_SOURCE_DIR) + "/tools/" + script}) {
    if (!std::filesystem::exists(path)) continue;
    const std::string cmd =
        fmt::format("/usr/bin/python3 '{}' '{}' >/dev/null 2>&1", path, dir.string());
    if (std::system(cmd.c_str()) != 0 && !Progress::quiet_default())
      fmt::print(stderr, "warning: plotting failed ({}); the results are in the CSV files\n", cmd);
    return;
  }
}

}  // namespace rcdem::io
