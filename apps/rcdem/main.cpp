// rcdem command line: generate | print-schema (run, calibrate and study arrive with the solver).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <iostream>

#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/io/atomic_file.hpp"
#include "rcdem/io/run_directory.hpp"
#include "rcdem/io/scenario.hpp"
#include "rcdem/io/schema.hpp"
#include "rcdem/io/specimen_output.hpp"
#include "rcdem/solver/run.hpp"
#include "rcdem/specimens/specimen.hpp"

namespace fs = std::filesystem;

namespace {

fs::path default_output(const fs::path& scenario) { return fs::path("results") / scenario.stem(); }

void write_specimen(const rcdem::Scenario& scenario, const fs::path& out,
                    std::chrono::steady_clock::time_point start);

int generate(const fs::path& scenario_path, fs::path out, bool force) {
  const auto start = std::chrono::steady_clock::now();
  const rcdem::Scenario scenario = rcdem::load_scenario(scenario_path);
  if (out.empty()) out = default_output(scenario_path);
  const bool created = rcdem::io::prepare_output_directory(out, force);
  try {
    write_specimen(scenario, out, start);
  } catch (...) {
    rcdem::io::remove_if_created_and_empty(out, created);
    throw;
  }
  return 0;
}

void write_specimen(const rcdem::Scenario& scenario, const fs::path& out,
                    std::chrono::steady_clock::time_point start) {
  const rcdem::Specimen specimen = rcdem::build_specimen(scenario);
  rcdem::io::write_file_atomically(out / "scenario.toml", scenario.text);
  rcdem::io::write_particles_vtu(out / "particles.vtu", specimen, scenario.output.binary_vtu);
  if (scenario.output.write_facets)
    rcdem::io::write_facets_vtu(out / "facets.vtu", specimen, scenario.output.binary_vtu);
  auto summary = rcdem::io::specimen_summary(scenario, specimen);
  summary["seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rcdem::io::write_file_atomically(out / "summary.json", summary.dump(2) + "\n");

  if (!rcdem::Progress::quiet_default()) {
    const auto& p = summary["particles"];
    fmt::print(
        "{}: {} aggregate + {} mortar + {} steel particles, {} contacts ({:.2f} per "
        "particle), {} local points ({:.2f} per contact), porosity {:.4f}, {:.1f} s\n"
        "written to {}\n",
        scenario.source.string(), p["aggregate"].get<long>(), p["mortar"].get<long>(),
        p["steel"].get<long>(), summary["contacts"].get<long>(),
        summary["contacts_per_particle"].get<double>(), summary["local_points"].get<long>(),
        summary["local_points_per_contact"].get<double>(), summary["porosity"].get<double>(),
        summary["seconds"].get<double>(), out.string());
  }
}

int run(const fs::path& scenario_path, fs::path out, bool force) {
  const rcdem::Scenario scenario = rcdem::load_scenario(scenario_path);
  rcdem::validate_run(scenario);
  if (out.empty()) out = default_output(scenario_path);
  const bool created = rcdem::io::prepare_output_directory(out, force);
  try {
    rcdem::io::write_file_atomically(out / "scenario.toml", scenario.text);
    rcdem::run_scenario(scenario, out);
  } catch (...) {
    rcdem::io::remove_if_created_and_empty(out, created);
    throw;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rcdem: 3D rigid-particle model for reinforced-concrete fracture"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string(RCDEM_VERSION) + " (" + RCDEM_GIT_HASH + ")");
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "No progress or summary lines");

  fs::path scenario, out;
  bool force = false;
  auto* gen = app.add_subcommand("generate", "Generate a specimen and its VGCM-3D contact network");
  gen->add_option("scenario", scenario, "Scenario file (TOML)")->required();
  gen->add_option("-o,--output", out, "Output directory (default results/<scenario name>)");
  gen->add_flag("--force", force, "Overwrite the results in a non-empty output directory");

  auto* runc = app.add_subcommand("run", "Generate the specimen and run the loading test");
  runc->add_option("scenario", scenario, "Scenario file (TOML)")->required();
  runc->add_option("-o,--output", out, "Output directory (default results/<scenario name>)");
  runc->add_flag("--force", force, "Overwrite the results in a non-empty output directory");

  auto* schema = app.add_subcommand("print-schema", "Print a documented scenario template");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  rcdem::Progress::set_quiet_default(quiet);
  try {
    if (*gen) return generate(scenario, out, force);
    if (*runc) return run(scenario, out, force);
    if (*schema) {
      rcdem::io::scenario_schema().print_template(std::cout);
      return 0;
    }
  } catch (const rcdem::Error& e) {
    std::cerr << "rcdem: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "rcdem: internal error: " << e.what() << "\n";
    return 3;
  }
  return 0;
}
