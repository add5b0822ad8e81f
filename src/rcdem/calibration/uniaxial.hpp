#pragma once
// The uniaxial compression and tension tests of the calibration (paper 3, Figure 7; SPEC 9), set
// up on a cube from a base scenario (its generation and contact parameters), run, and read:
// E (secant at 40% of the peak), nu (lateral over axial strain at 10% of the peak, where the
// response is still elastic), both from the interior gauge, the strength, and the stress-strain
// (face gauge) and damage-strain curves.
#include <filesystem>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"

namespace rcdem {

enum class UniaxialMode { Compression, Tension };

// The paper's calibration cube (Table 1's specimen), the default and the reference for the
// loading of larger cubes.
constexpr Real kPaperCubeSide = 0.160;  // m

struct UniaxialOptions {
  Real size = kPaperCubeSide;  // cube side [m]
  Real rate_factor = 1.0;      // multiplies the loading rates below (quasi-static checks)
  // Axial strain rates [1/s] on cubes up to the paper's 160 mm; above it they fall as 160 mm /
  // side (uniaxial_scenario).
  Real compression_rate = 1.25;
  Real tension_rate = 0.125;
  std::int64_t snapshots = 4;
  // Stop once the load has fallen below this fraction of the peak; 0 = the full post-peak curve
  // (60% in compression, 30% in tension). A search needs only the peak, E and nu.
  Real stop_after_peak = 0.0;
};

struct CurvePoint {
  Real strain;   // axial, from the face gauges over the true gauge length, positive in the
                 // test's sense (io/strain_gauges.hpp)
  Real stress;   // load / loaded area [Pa], positive in the test's sense
  Real lateral;  // mean lateral strain (x and y), face gauges
  Real damaged;  // fraction of local points with 0 < D < 1
  Real broken;   // fraction with D = 1
  Real interior_strain = 0.0;   // axial, from the interior gauge (least-squares fit)
  Real interior_lateral = 0.0;  // mean lateral, interior gauge
};

struct UniaxialResult {
  UniaxialMode mode;
  Real strength = 0.0;  // peak stress [Pa]
  Real strain_at_peak = 0.0;
  // E and nu from the interior gauge: the bulk material, whatever the cube's size (docs/model.md
  // 7).
  Real E = 0.0;             // secant modulus at 40% of the peak [Pa]
  Real nu = 0.0;            // -lateral / axial strain at 10% of the peak (elastic range)
  Real nu_at_40 = 0.0;      // the same ratio at 40% of the peak (includes microcracking)
  Real E_face_gauge = 0.0;  // E and nu read the same way from the face gauges
  Real nu_face_gauge = 0.0;
  Real loaded_area = 0.0;   // the platen face's boundary area [m^2]
  Real gauge_length = 0.0;  // the axial face gauge's length [m]
  Real kinetic_over_strain_at_peak = 0.0;
  Real energy_balance_error = 0.0;
  std::vector<CurvePoint> curve;
};

// The test's scenario: the base's specimen generation and contact parameters on a cube, with
// platens (frictionless for compression, glued for tension), loading and stop rules.
Scenario uniaxial_scenario(const Scenario& base, UniaxialMode mode, const UniaxialOptions& opt);

// Runs the test in `dir` (created) and reads its curve.
UniaxialResult run_uniaxial(const Scenario& base, UniaxialMode mode, const UniaxialOptions& opt,
                            const std::filesystem::path& dir);

// Reads E, nu and the strength from a curve (exposed for tests).
void analyse_curve(UniaxialResult& r);

const char* mode_name(UniaxialMode m);

// A curve as CSV: strain, stress_Pa, lateral_strain, damaged_fraction, broken_fraction,
// interior_strain, interior_lateral_strain.
void write_curve_csv(const std::filesystem::path& path, const std::vector<CurvePoint>& curve);

}  // namespace rcdem
