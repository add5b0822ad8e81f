#pragma once
// A scenario's text with keys set from the command line (`--set KEY=VALUE`, `--seed N`): each
// value written where the file sets the key, else under its section's header, else in a section
// appended, everything else kept to the byte (order, comments, includes). So the run directory's
// scenario.toml is the scenario as run, and resuming it or running it again gives the same run.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"

namespace rcdem::config {

// Splits and checks the syntax of `--set` items; refuses an item without '=', an empty key, a
// value that is neither TOML nor a bare word, and a key given twice.
std::vector<Override> parse_overrides(const std::vector<std::string>& items);

// `text` (from `source`, named in messages) with `o.key` = `o.value`. Refuses (Error naming the
// source) a text it cannot edit that way, e.g. a key set inside an inline table.
std::string with_override(const std::string& text, const std::string& source, const Override& o);

// `text` with generation.seed = seed.
std::string with_generation_seed(const std::string& text, const std::string& source,
                                 std::uint64_t seed);

// The scenario file `path` on packing `seed` (none: its own) with `overrides` applied, each
// checked against the schema as if written in the file and named in errors as coming from the
// command line; its text the one run.
Scenario load_scenario_on_seed(const std::filesystem::path& path,
                               std::optional<std::uint64_t> seed,
                               const std::vector<std::string>& overrides = {});

}  // namespace rcdem::config
