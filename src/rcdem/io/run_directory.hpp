#pragma once
// The output directory of a command: created if missing, never overwritten without --force.
#include <filesystem>

namespace rcdem::io {

// Creates `dir` (and parents). Refuses a non-empty directory unless `force`, and a directory that
// cannot be written, with a message naming it.
void prepare_output_directory(const std::filesystem::path& dir, bool force);

}  // namespace rcdem::io
