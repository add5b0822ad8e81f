#pragma once
// A scenario run on another packing: its text with generation.seed set, everything else kept to
// the byte (order, comments, includes), so that the run directory's scenario.toml is the scenario
// as run and resuming it or running it again gives the same packing (`rcdem run --seed`, a
// study's `--seeds`).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "rcdem/config/scenario.hpp"

namespace rcdem::config {

// `text` (from `source`, named in messages) with generation.seed = seed: the value replaced where
// the file sets it, else a `seed = ...` line added under its [generation] header, else a
// [generation] table appended. Refuses (Error naming the source) a text it cannot edit that way,
// e.g. a seed set inside an inline table it would have to rewrite.
std::string with_generation_seed(const std::string& text, const std::string& source,
                                 std::uint64_t seed);

// The scenario file `path` on packing `seed` (none: the file as it is), its text the one run.
Scenario load_scenario_on_seed(const std::filesystem::path& path,
                               std::optional<std::uint64_t> seed);

}  // namespace rcdem::config
