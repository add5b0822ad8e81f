#pragma once
// Runs one of rcdem's own Python tools (tools/*.py, Debian's python3-matplotlib) on a result
// directory, without a shell (core/child_process.hpp), from the installed location or the source
// tree the binary was built from. The tool's output goes to DIR/<log>; a Ctrl-C that killed the
// tool ends rcdem too.
#include <filesystem>
#include <string>

namespace rcdem::io {

// Plots are a convenience beside the CSV files: a missing tool or a failed plot is a warning
// naming the cause and the log, never an error. The log is removed when the plot succeeded.
void run_plot_tool(const std::string& script, const std::filesystem::path& dir);

// A report is what the command was asked for: a failure is an Error with the tool's last line of
// output and the log's path (DIR/report.log, kept).
void run_report_tool(const std::string& script, const std::filesystem::path& dir);

}  // namespace rcdem::io
