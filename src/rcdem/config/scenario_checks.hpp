#pragma once
// Checks across a converted scenario's keys that its values, each admissible on its own, make a
// model that can be built: how many bodies and how much memory it needs, whether its bars overlap
// each other or the notch, whether its plates overlap. Each refusal is an Error naming the file,
// line and key (Scenario::key_line) and what was expected.
#include <cstdint>
#include <string>

#include "rcdem/config/scenario.hpp"

namespace rcdem::config {

// A run's peak memory per body (particle or interface sphere), measured: the full AN4 NL-B beam
// (26,478 bodies, 171,668 contacts) peaks at 478 MB resident after 20 steps, 18.1 kB each
// (docs/model.md, "Model size": tools/regenerate_docs.sh model_checks).
inline constexpr double kBytesPerParticle = 18.1e3;
// More plates or bars than any test needs is a typo or a generated file gone wrong; the bar
// checks are pairwise.
inline constexpr int kMaxPlates = 64;
inline constexpr int kMaxBars = 4096;

// "file:line" where `key` was set, or the file alone for a default.
std::string key_location(const Scenario& s, const std::string& key);

// Bodies (particles, interface spheres, cylinders) against generation.max_particles, and their
// memory against this machine's physical memory.
void check_model_size(const Scenario& s);

// Bars against one another (their steel may not overlap: axes at least r1 + r2 apart) and
// against the notch (no bar may cut through it).
void check_bar_layout(const Scenario& s);

// Plates: at most kMaxPlates, and no two on one face whose rectangles overlap.
void check_plate_layout(const Scenario& s);

}  // namespace rcdem::config
