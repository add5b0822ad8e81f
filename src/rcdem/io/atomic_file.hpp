#pragma once
// Result files are written to a temporary name in the same directory, flushed, then renamed over
// the final name, so an interrupted run never leaves a half-written file behind.
#include <filesystem>
#include <string_view>

namespace rcdem::io {

// Throws rcdem::Error "cannot write 'PATH': REASON" on failure (the temporary is removed).
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

// The same, returning 0 or the errno of the failure, for callers with their own message.
int try_write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace rcdem::io
