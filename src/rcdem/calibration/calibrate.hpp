#pragma once
// Calibration (paper 3, SPEC 9): uniaxial compression and tension on a cube give E, nu, sigma_c
// and sigma_t for a set of contact parameters; with a target, the contact parameters are searched
// until all four are within a tolerance (beyond the paper, which calibrated by hand).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "rcdem/calibration/uniaxial.hpp"

namespace rcdem {

struct MacroProperties {
  Real E = 0.0, nu = 0.0, sigma_c = 0.0, sigma_t = 0.0;
};

// Parses "E=34.2e9,nu=0.15,sigma_c=91.2e6,sigma_t=4.0e6" (SI); all four are required.
MacroProperties parse_macro_properties(const std::string& text);

// The contact parameter that the search moves, with tau, towards sigma_t (docs/model.md 7).
enum class TensionLever { FractureEnergy, TensileStrength };

// "G_fn" or "sigma_nt"; anything else is refused naming the option.
TensionLever parse_tension_lever(const std::string& text);

struct CalibrationOptions {
  UniaxialOptions uniaxial;
  std::optional<MacroProperties> target;
  TensionLever tension_lever = TensionLever::FractureEnergy;
  Real tolerance = 0.05;
  int max_iterations = 8;
};

struct CalibrationResult {
  ContactParameters parameters;
  MacroProperties measured;
  bool converged = false;
  int iterations = 0;
};

// The parameter update of one search iteration (exposed for tests): the elastic pair from the
// closed-form relations of a random isotropic network of normal and shear springs,
// nu = (1 - alpha) / (4 + alpha) and E ~ E_bar (2 + 3 alpha) / (4 + alpha), each corrected by the
// ratio measured on this packing; the strengths in proportion to their misfit (the search then
// replaces tau and its tension lever by StrengthSecant's step, calibration/strength_secant.hpp).
ContactParameters update_parameters(const ContactParameters& p, const MacroProperties& measured,
                                    const MacroProperties& target);

// Runs the tests (and the search, with a target) in `out`, writing calibration.json, the curves
// (CSV), a contact fragment for other scenarios (calibrated_contact.toml) and, if Python with
// matplotlib is there, the Figure 7 plot.
CalibrationResult calibrate(const Scenario& base, const CalibrationOptions& opt,
                            const std::filesystem::path& out);

}  // namespace rcdem
