#pragma once
// What `rcdem generate` writes: particles.vtu, facets.vtu and summary.json.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/specimens/specimen.hpp"

namespace rcdem::io {

// Counts, porosity, volumes and the packing's quality figures. Wall-clock `seconds` is added by
// the caller, last, as the only field that differs between two runs of the same scenario.
nlohmann::ordered_json specimen_summary(const Scenario& scenario, const Specimen& specimen);

// The contacts in the order their facets are written: by vertex count, then by index, so that a
// reader that groups cells by type and size (meshio) gets one block per vertex count instead of
// one per change of count. Each facet file's `contact` array gives the index back.
std::vector<Index> facet_order(const ContactNetwork& contacts);

void write_particles_vtu(const std::filesystem::path& path, const Specimen& specimen, bool binary);
void write_facets_vtu(const std::filesystem::path& path, const Specimen& specimen, bool binary);

}  // namespace rcdem::io
