#pragma once
// Result files are written to a temporary name in the same directory, flushed, then renamed over
// the final name, so an interrupted run never leaves a half-written file behind.
#include <filesystem>
#include <string_view>

namespace rcdem::io {

void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace rcdem::io
