#pragma once
// Specimen builders registered by name ("box", "beam", later "pull_out"): adding a specimen is one
// function and one row in the table in specimen_registry.cpp.
#include <string>
#include <vector>

#include "rcdem/config/specimen_geometry.hpp"

namespace rcdem {

struct Scenario;

struct SpecimenBuilder {
  std::string name;
  std::string doc;
  SpecimenGeometry (*geometry)(const Scenario&);
};

const std::vector<SpecimenBuilder>& specimen_builders();
const SpecimenBuilder& find_specimen_builder(const std::string& name);

// Shape-specific checks, run when a scenario is loaded.
void validate_specimen(const Scenario& scenario);
SpecimenGeometry specimen_geometry(const Scenario& scenario);

}  // namespace rcdem
