#pragma once
// Runs one of the Python plotting tools (tools/*.py, Debian's python3-matplotlib) on a result
// directory. Plots are a convenience beside the CSV files: a missing tool or a failed plot is a
// warning, never an error.
#include <filesystem>
#include <string>

namespace rcdem::io {

void run_plot_tool(const std::string& script, const std::filesystem::path& dir);

}  // namespace rcdem::io
