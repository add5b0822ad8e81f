#pragma once
// Reading a scenario's text so that no file can crash, hang or exhaust rcdem before the TOML
// parser sees it: only regular files below a size cap are read (a FIFO would block open(), a
// device such as /dev/zero never ends), and keys, headers, arrays and inline tables nested deeper
// than any scenario needs are refused before parsing (toml++ recurses on dotted keys and would
// overflow the stack on tens of thousands of levels).
#include <toml++/toml.h>

#include <cstddef>
#include <filesystem>
#include <string>

namespace rcdem::config {

// Scenario files and their includes are a few kB; this leaves room for long generated arrays.
inline constexpr std::size_t kMaxScenarioBytes = 4u << 20;
// The schema's deepest key has 3 segments (bars.NAME.key); a value nests at most one array.
inline constexpr int kMaxKeyDepth = 16;
inline constexpr int kMaxValueDepth = 16;

// The whole text of `path`, which `role` ("scenario", "include") names in the messages. Refuses
// a missing, non-regular, unreadable or oversized file with an Error naming `referrer` (the file
// and line that asked for it, e.g. "a.toml:3: key 'include'") or, when empty, the path itself.
std::string read_scenario_file(const std::filesystem::path& path, const std::string& role,
                               const std::string& referrer = "");

// Refuses (Error "source:line: ...") a text whose keys or values nest deeper than the limits
// above. A lexical scan, not a parser: it skips strings and comments and leaves every other
// syntax error to toml++.
void check_scenario_nesting(const std::string& text, const std::string& source);

// `text` parsed as TOML after the nesting check; a syntax error is refused as "source:line: ...".
toml::table parse_scenario_toml(const std::string& text, const std::string& source);

}  // namespace rcdem::config
