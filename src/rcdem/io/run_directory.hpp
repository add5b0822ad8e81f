#pragma once
// The output directory of a command: created if missing, never overwritten without --force.
#include <filesystem>

namespace rcdem::io {

// Creates `dir` (and parents). Refuses a non-empty directory unless `force`, and a directory that
// cannot be written, with a message naming it. Returns whether it created the directory.
bool prepare_output_directory(const std::filesystem::path& dir, bool force);

// After a failure: removes `dir` if this command created it and it is still empty.
void remove_if_created_and_empty(const std::filesystem::path& dir, bool created) noexcept;

}  // namespace rcdem::io
