// rcdem command line: generate | run | calibrate | study | print-schema.
#include <fmt/format.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "rcdem/calibration/calibrate.hpp"
#include "rcdem/config/scenario.hpp"
#include "rcdem/config/scenario_overrides.hpp"
#include "rcdem/config/schema.hpp"
#include "rcdem/core/build_info.hpp"
#include "rcdem/core/child_process.hpp"
#include "rcdem/core/error.hpp"
#if defined(RCDEM_WITH_MPI)
#include "rcdem/mpi/mpi_communicator.hpp"
#include "rcdem/mpi/peer_watch.hpp"
#endif
#include "rcdem/core/huge_pages.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/core/thread_waiting.hpp"
#include "rcdem/io/atomic_file.hpp"
#include "rcdem/io/specimen_output.hpp"
#include "rcdem/run/distributed_run.hpp"
#include "rcdem/run/run.hpp"
#include "rcdem/run/run_directory.hpp"
#include "rcdem/run/run_signals.hpp"
#include "rcdem/specimens/specimen.hpp"
#include "rcdem/study/study.hpp"

namespace fs = std::filesystem;

namespace {

fs::path default_output(const fs::path& scenario) { return fs::path("results") / scenario.stem(); }

void write_specimen(const rcdem::Scenario& scenario, const fs::path& out,
                    std::chrono::steady_clock::time_point start);

int generate(const fs::path& scenario_path, fs::path out, bool force) {
  const auto start = std::chrono::steady_clock::now();
  const rcdem::Scenario scenario = rcdem::load_scenario(scenario_path);
  if (out.empty()) out = default_output(scenario_path);
  rcdem::io::OutputDirectory dir(out, force, {scenario_path});
  try {
    write_specimen(scenario, out, start);
  } catch (const rcdem::Error& e) {
    rcdem::rethrow_naming(scenario_path.string(), e);
  }
  dir.commit();
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

// --checkpoint-every: a step count ("5000") or a wall time ("90s", "10min", "2h"); "0" = only
// on SIGINT/SIGTERM.
void parse_checkpoint_every(const std::string& text, rcdem::RunOptions& o) {
  const auto bad = [&] {
    rcdem::fail(
        "--checkpoint-every '{}': expected a step count (e.g. 5000) or a wall time (e.g. 90s, "
        "10min, 2h); 0 = only on SIGINT/SIGTERM",
        text);
  };
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !std::isfinite(v) || v < 0.0) bad();
  const std::string unit = end;
  o.checkpoint_every_steps = 0;
  o.checkpoint_every_seconds = 0.0;
  if (unit.empty()) {
    if (v != std::floor(v) || v > 1e15) bad();
    o.checkpoint_every_steps = static_cast<std::int64_t>(v);
  } else if (unit == "s") {
    o.checkpoint_every_seconds = v;
  } else if (unit == "min") {
    o.checkpoint_every_seconds = 60.0 * v;
  } else if (unit == "h") {
    o.checkpoint_every_seconds = 3600.0 * v;
  } else {
    bad();
  }
}

// --threads: "auto" (0: follow the free cores, up to OMP_NUM_THREADS or the cores) or a count.
int parse_threads(const std::string& text) {
  if (text == "auto") return 0;
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0' || errno != 0 || v < 1 || v > 4096)
    rcdem::fail("--threads '{}': expected auto or a whole number of threads from 1 to 4096", text);
  return static_cast<int>(v);
}

// The --checkpoint-every a run was started (or last resumed) with, from its manifest; empty if
// it recorded none.
std::string recorded_checkpoint_every(const fs::path& dir) {
  std::ifstream in(dir / "manifest.json");
  const auto m = nlohmann::json::parse(in, nullptr, false);
  if (m.is_discarded() || !m.is_object() || !m.contains("checkpoint_every") ||
      !m["checkpoint_every"].is_string())
    return "";
  return m["checkpoint_every"].get<std::string>();
}

// A --force killed during its set-up left the earlier run aside (DIR/.rcdem-replaced): it is what
// --resume continues, so it is put back first.
void restore_interrupted_force(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir / rcdem::io::OutputDirectory::kReplacedName, ec)) return;
  const rcdem::io::RunLock lock(dir, true);
  if (rcdem::io::restore_replaced_results(dir) && !rcdem::Progress::quiet_default())
    fmt::print(stderr,
               "rcdem: '{}': a --force was interrupted during its set-up; the earlier run it "
               "was replacing is restored\n",
               dir.string());
}

// Rank 0's group in `mpirun -np N rcdem run` (run/distributed_run.hpp); none otherwise.
rcdem::RankGroup* g_ranks = nullptr;

int run(const fs::path& scenario_path, fs::path out, bool force, const fs::path& resume,
        std::string checkpoint_every, bool checkpoint_every_given,
        std::optional<std::uint64_t> seed, const std::vector<std::string>& sets,
        const std::string& threads, const std::vector<std::string>& command) {
  rcdem::RunOptions options;
  options.ranks = g_ranks;
  options.handle_signals = true;
  options.threads = parse_threads(threads);
  options.command = command;
  // A resumed run keeps its interval unless told otherwise (issue 28).
  if (!resume.empty() && !checkpoint_every_given) {
    const std::string recorded = recorded_checkpoint_every(resume);
    if (!recorded.empty()) checkpoint_every = recorded;
  }
  parse_checkpoint_every(checkpoint_every, options);
  options.checkpoint_every_text = checkpoint_every;
  rcdem::RunSummary r;
  if (!resume.empty()) {
    if (!scenario_path.empty())
      rcdem::fail("run: give a scenario or --resume DIR, not both (DIR holds its scenario)");
    if (!out.empty() || force || seed || !sets.empty())
      rcdem::fail(
          "run --resume '{}': the run continues in its own directory with its own scenario; drop "
          "-o/--force/--seed/--set",
          resume.string());
    restore_interrupted_force(resume);
    if (rcdem::complete_finished_run(resume)) {
      if (!rcdem::Progress::quiet_default())
        fmt::print(stderr,
                   "rcdem: '{}': the run had finished (summary.json) but was stopped before its "
                   "manifest's last update; the manifest is completed, nothing to resume\n",
                   resume.string());
      return 0;
    }
    const rcdem::Scenario scenario = rcdem::run_directory_scenario(resume);
    rcdem::validate_run(scenario);
    if (::access(resume.c_str(), W_OK | X_OK) != 0)
      rcdem::fail("run directory '{}' is not writable: {}", resume.string(), std::strerror(errno));
    options.resume = true;
    r = rcdem::run_scenario(scenario, resume, options);
  } else {
    if (scenario_path.empty()) rcdem::fail("run: give a scenario file (or --resume DIR)");
    const rcdem::Scenario scenario =
        rcdem::config::load_scenario_on_seed(scenario_path, seed, sets);
    rcdem::validate_run(scenario);
    if (out.empty()) out = default_output(scenario_path);
    rcdem::io::OutputDirectory dir(out, force, {scenario_path});
    options.lock_held = true;
    options.on_started = [&dir] { dir.commit(); };
    r = rcdem::run_scenario(scenario, out, options);
  }
  // Interrupted: the shell's convention for a death by that signal (130 for SIGINT).
  return r.stop_reason == "interrupted" ? 128 + r.signal : 0;
}

// The cube's side: --size, else the base scenario's specimen when it is a cube (a file written
// for a resolution names its cube), else the paper's 160 mm.
double calibration_cube_side(const rcdem::Scenario& base, std::optional<double> size) {
  if (size) return *size;
  const auto& s = base.specimen;
  const bool cube =
      s.shape == "box" && s.size.x() > 0.0 && s.size.x() == s.size.y() && s.size.y() == s.size.z();
  return cube ? s.size.x() : rcdem::kPaperCubeSide;
}

int calibrate(const fs::path& scenario_path, fs::path out, bool force,
              std::optional<double> size_option, double rate_factor,
              const std::vector<std::string>& sets, const std::string& target, double tolerance,
              int iterations, bool peak_only, const std::string& lever) {
  rcdem::Scenario base = rcdem::config::load_scenario_on_seed(scenario_path, std::nullopt, sets);
  const double size = calibration_cube_side(base, size_option);
  rcdem::CalibrationOptions opt;
  opt.uniaxial.size = size;
  opt.uniaxial.rate_factor = rate_factor;
  if (peak_only) {
    opt.uniaxial.stop_after_peak = 0.85;
    opt.uniaxial.snapshots = 0;
  }
  opt.tolerance = tolerance;
  opt.max_iterations = iterations;
  opt.tension_lever = rcdem::parse_tension_lever(lever);
  if (!target.empty()) opt.target = rcdem::parse_macro_properties(target);
  const auto largest = std::max(base.generation.aggregate_d_max, base.generation.mortar_d_max);
  if (size < 4.0 * largest)
    rcdem::fail("--size {} m: a cube needs at least four of the largest diameters ({} m) per side",
                size, 4.0 * largest);
  if (out.empty()) out = fs::path("results") / ("calibrate_" + scenario_path.stem().string());
  rcdem::io::OutputDirectory dir(out, force, {scenario_path});
  dir.commit();  // a calibration's partial outputs (its iterations) are kept if it fails
  const auto r = rcdem::calibrate(base, opt, out);
  fmt::print(
      "E = {:.4g} GPa, nu = {:.4f}, sigma_c = {:.4g} MPa, sigma_t = {:.4g} MPa "
      "(sigma_c / sigma_t = {:.1f}){}\nwritten to {}\n",
      r.measured.E / 1e9, r.measured.nu, r.measured.sigma_c / 1e6, r.measured.sigma_t / 1e6,
      r.measured.sigma_c / r.measured.sigma_t,
      opt.target ? (r.converged ? "; converged" : "; NOT converged") : "", out.string());
  return opt.target && !r.converged ? 4 : 0;
}

// A study directory is resumed (finished cases kept) when it holds a study.json; any other
// non-empty directory is refused unless --force.
int study(const std::string& name, fs::path scenarios, fs::path out, bool force, bool quick,
          const std::vector<std::string>& cases, const std::vector<std::uint64_t>& seeds,
          const std::vector<std::string>& sets, const std::string& sweep, int jobs) {
  rcdem::StudyOptions o;
  o.label = name + (quick ? " (quick)" : "");
  o.scenarios = scenarios.empty() ? rcdem::builtin_study_scenarios(name, quick) : scenarios;
  if (!fs::is_directory(o.scenarios))
    rcdem::fail("--scenarios '{}': not a directory of scenarios", o.scenarios.string());
  // The report: the size series' (its name, whatever its scenarios); else the paper's tables and
  // figures where every case is a paper beam, or a table and figure of the cases as they are
  // (tools/study_report.py decides).
  if (name == "size_series")
    o.report_script = "size_series_report.py";
  else if (name == "three_point_bending" || !scenarios.empty())
    o.report_script = "study_report.py";
  if (out.empty()) out = fs::path("results") / ("study_" + name + (quick ? "_quick" : ""));
  o.out = out;
  o.cases = cases;
  o.seeds = seeds;
  o.sets = sets;
  o.sweep = sweep;
  o.force = force;
  // Quick cases are small: one per core, one thread each, beats one case on every core.
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  o.jobs = jobs > 0 ? jobs : quick ? cores : 1;
  o.threads_per_job = std::max(1, cores / o.jobs);
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::exists(out / "study.json", ec) && !fs::is_empty(out, ec) &&
      !force)
    rcdem::fail(
        "output directory '{}' is not empty and holds no study (study.json); use --force to "
        "write into it",
        out.string());
  rcdem::io::prepare_output_directory(out);
  const int failed = rcdem::run_study(o);
  return failed == 0 ? 0 : failed < 0 ? 130 : 5;
}

// An error is one line, whatever the names in it hold: control characters (a newline in a file
// name) written as C escapes.
std::string one_line(const std::string& text) {
  std::string out;
  for (const char ch : text) {
    const auto u = static_cast<unsigned char>(ch);
    if (ch == '\n')
      out += "\\n";
    else if (ch == '\r')
      out += "\\r";
    else if (ch == '\t')
      out += "\\t";
    else if (u < 0x20 || u == 0x7f)
      out += fmt::format("\\x{:02x}", u);
    else
      out += ch;
  }
  return out;
}

// The first word that is not an option, when it names no subcommand (CLI11 would only say that
// one is required).
const char* unknown_subcommand(const CLI::App& app, int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    if (argv[k][0] == '-') continue;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
      if (sub->check_name(argv[k])) return nullptr;
    return argv[k];
  }
  return nullptr;
}

}  // namespace

#if defined(RCDEM_WITH_MPI)
// A rank other than 0 of `mpirun -np N rcdem run`: builds and follows rank 0, which reports the
// run and every failure they share; a failure of this rank alone ends every rank. Stop signals are
// rank 0's to act on (mpirun passes them to every rank).
int follow(rcdem::RankGroup& group, const std::string& threads) {
  std::signal(SIGINT, SIG_IGN);
  std::signal(SIGTERM, SIG_IGN);
  rcdem::Progress::set_quiet_default(true);
  try {
    return rcdem::follow_run(group, threads == "auto" ? 0 : parse_threads(threads));
  } catch (const std::exception& e) {
    std::cerr << "rcdem: error on rank " << group.comm().rank() << ": " << one_line(e.what())
              << "\n";
    group.comm().abort(1);
  }
  return 1;
}
#endif

int main(int argc, char** argv) {
  rcdem::prefer_huge_pages(argv);          // may start again: first (core/huge_pages.hpp)
  rcdem::prefer_passive_thread_waiting();  // before any OpenMP call (core/thread_waiting.hpp)
  // A file-size limit (ulimit -f) then fails a write with EFBIG, which rcdem reports like any
  // write failure, instead of killing the run without a word or a checkpoint.
  std::signal(SIGXFSZ, SIG_IGN);
  rcdem::stop_with_parent_process();
#if defined(RCDEM_WITH_MPI)
  rcdem::MpiSession mpi(argc, argv);
  // Under mpirun every rank parses the same command line: rank 0 alone reports its errors.
  const bool report = mpi.rank() == 0;
#else
  const bool report = true;
#endif
  CLI::App app{"rcdem: 3D rigid-particle model for reinforced-concrete fracture"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "rcdem " + std::string(rcdem::build_version()) + " (" +
                                        rcdem::build_git_hash() + ", " + rcdem::build_flavour() +
                                        ")");
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "No progress or summary lines");
  app.fallthrough();  // -q after the subcommand too

  fs::path scenario, out;
  bool force = false;
  auto* gen = app.add_subcommand("generate", "Generate a specimen and its VGCM-3D contact network");
  gen->add_option("scenario", scenario, "Scenario file (TOML)")->required();
  gen->add_option("-o,--output", out, "Output directory (default results/<scenario name>)");
  gen->add_flag("--force", force, "Overwrite the results in a non-empty output directory");

  fs::path resume;
  std::string checkpoint_every = "10min";
  auto* runc = app.add_subcommand(
      "run",
      "Generate the specimen and run the loading test (checkpointed; Ctrl-C saves and stops)");
  runc->add_option("scenario", scenario, "Scenario file (TOML)");
  runc->add_option("-o,--output", out, "Output directory (default results/<scenario name>)");
  runc->add_flag("--force", force, "Overwrite the results in a non-empty output directory");
  runc->add_option("--resume", resume,
                   "Continue the interrupted run in DIR from its latest checkpoint")
      ->type_name("DIR");
  runc->add_option("--checkpoint-every", checkpoint_every,
                   "Checkpoint every N steps or every T of wall time (e.g. 5000, 90s, 10min, 2h; "
                   "0 = only on SIGINT/SIGTERM)")
      ->type_name("N|T")
      ->capture_default_str();
  std::vector<std::string> sets;
  const char* set_help =
      "Set a scenario key as if written in the file: KEY=VALUE (e.g. solver.damping=0.3, "
      "plates.top.velocity=-0.05, specimen.shape=beam); repeatable";
  runc->add_option("--set", sets, set_help)->type_name("KEY=VALUE");
  std::uint64_t run_seed = 0;
  runc->add_option("--seed", run_seed,
                   "Run on another packing: generation.seed set to N (kept in DIR/scenario.toml)")
      ->check(CLI::Range(std::uint64_t{0}, std::uint64_t{9'000'000'000'000'000}));
  std::string run_threads = "auto";
  runc->add_option("--threads", run_threads,
                   "Threads: auto follows the cores other work leaves free, up to OMP_NUM_THREADS "
                   "(or every core); N runs exactly N. The results are the same bits at any count")
      ->type_name("auto|N")
      ->capture_default_str();

  std::optional<double> size;
  double rate_factor = 1.0, tolerance = 0.05;
  int iterations = 8;
  std::string target;
  auto* cal = app.add_subcommand(
      "calibrate", "Uniaxial compression and tension on a cube: E, nu, sigma_c, sigma_t (SPEC 9)");
  cal->add_option("scenario", scenario,
                  "Base scenario: generation and contact parameters (e.g. "
                  "examples/uniaxial/cube160.toml)")
      ->required();
  cal->add_option("-o,--output", out, "Output directory (default results/calibrate_<name>)");
  cal->add_flag("--force", force, "Overwrite the results in a non-empty output directory");
  cal->add_option("--size", size,
                  "Cube side [m] (default: the scenario's specimen if it is a cube, else 0.16)")
      ->check(CLI::PositiveNumber);
  cal->add_option("--rate-factor", rate_factor, "Multiply the loading rates (quasi-static checks)")
      ->check(CLI::PositiveNumber);
  cal->add_option("--set", sets, set_help)->type_name("KEY=VALUE");
  cal->add_option("--target", target,
                  "Search contact parameters for E=..,nu=..,sigma_c=..,sigma_t=.. (SI)");
  cal->add_option("--tolerance", tolerance, "Relative tolerance of the search")
      ->check(CLI::Range(0.001, 0.5));
  bool peak_only = false;
  cal->add_flag(
      "--peak-only", peak_only,
      "Stop each test soon after its peak (E, nu and strengths only; no post-peak curve)");
  cal->add_option("--iterations", iterations, "At most this many search iterations")
      ->check(CLI::Range(1, 50));
  std::string tension_lever = "G_fn";
  cal->add_option("--tension-lever", tension_lever,
                  "Contact parameter the search moves, with tau, towards sigma_t: G_fn (default) "
                  "or sigma_nt");

  std::string study_name;
  fs::path study_scenarios;
  bool quick = false;
  std::vector<std::string> cases;
  auto* stc = app.add_subcommand(
      "study", "Run a study's cases (resumable) and write its tables and figures");
  stc->add_option("name", study_name,
                  "Study: three_point_bending (paper 3, SPEC 10) or size_series (depths 100, 200, "
                  "400 mm; docs/size-series.md)")
      ->required();
  stc->add_option("-o,--output", out, "Study directory (default results/study_<name>[_quick])");
  stc->add_flag("--quick", quick,
                "Coarser particles and faster loading: the whole study in minutes (examples/<name>"
                "/study/quick)");
  stc->add_option("--cases", cases, "Run only these cases (e.g. AN0,AN2_NL-B)")->delimiter(',');
  std::vector<std::uint64_t> seeds;
  stc->add_option("--seeds", seeds,
                  "Run every case on each of these packings (generation.seed), e.g. 1,2,3: the "
                  "report gives means, standard deviations and ranges")
      ->delimiter(',')
      ->check(CLI::Range(std::uint64_t{0}, std::uint64_t{9'000'000'000'000'000}));
  stc->add_option("--scenarios", study_scenarios,
                  "A directory of scenarios to run instead of the built-in ones");
  stc->add_flag("--force", force, "Rerun finished cases");
  stc->add_option("--set", sets, std::string(set_help) + "; applied to every case")
      ->type_name("KEY=VALUE");
  std::string sweep;
  stc->add_option("--sweep", sweep,
                  "Run every case once per value of one key: KEY=V1,V2,... (e.g. "
                  "contact.sigma_nt=3e6,4.23e6,5.5e6), each case named <case>_<LEAF>=<V>")
      ->type_name("KEY=V1,V2,...");
  int jobs = 0;
  stc->add_option("-j,--jobs", jobs,
                  "Cases run side by side (default: one per core with --quick, else 1)")
      ->check(CLI::Range(1, 64));

  auto* schema = app.add_subcommand("print-schema", "Print a documented scenario template");

  if (const char* unknown = unknown_subcommand(app, argc, argv)) {
    std::string names;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
      names += (names.empty() ? "" : ", ") + sub->get_name();
    if (report)
      std::cerr << "rcdem: error: unknown command '" << one_line(unknown)
                << "' (the commands are: " << names << "; rcdem --help says more)\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return report ? app.exit(e) : 0;  // --help, --version
    if (report)
      std::cerr << "rcdem: error: " << one_line(e.what())
                << " (rcdem --help lists the commands and options)\n";
    return 2;
  }
  rcdem::Progress::set_quiet_default(quiet);
  std::unique_ptr<rcdem::Communicator> comm;
  std::unique_ptr<rcdem::RankGroup> group;
#if defined(RCDEM_WITH_MPI)
  if (mpi.size() > 1) {
    comm = std::make_unique<rcdem::MpiCommunicator>();
    if (!*runc) {
      if (comm->leader())
        std::cerr << "rcdem: error: only 'rcdem run' runs on several MPI ranks (this is one of "
                  << comm->size() << "); run the other commands without mpirun\n";
      return 2;
    }
    group = std::make_unique<rcdem::RankGroup>(*comm);
    if (!comm->leader()) return follow(*group, run_threads);
    g_ranks = group.get();
  }
  std::optional<rcdem::PeerWatch> watch;
  if (group)
    watch.emplace(
        [] {
          const int sig = rcdem::pending_stop_signal();
          return rcdem::StopRequest{sig, rcdem::signal_name(sig), rcdem::pending_stop_signal_ns(),
                                    rcdem::stop_signal_taken()};
        },
        (resume.empty() ? out : resume).string());
#endif
  try {
    if (*gen) return generate(scenario, out, force);
    if (*runc) {
      const int code =
          run(scenario, out, force, resume, checkpoint_every, runc->count("--checkpoint-every") > 0,
              runc->count("--seed") > 0 ? std::optional<std::uint64_t>(run_seed) : std::nullopt,
              sets, run_threads, std::vector<std::string>(argv, argv + argc));
      if (group) group->finish(0);
      return code;
    }
    if (*cal)
      return calibrate(scenario, out, force, size, rate_factor, sets, target, tolerance, iterations,
                       peak_only, tension_lever);
    if (*stc)
      return study(study_name, study_scenarios, out, force, quick, cases, seeds, sets, sweep, jobs);
    if (*schema) {
      rcdem::config::scenario_schema().print_template(std::cout);
      return 0;
    }
  } catch (const rcdem::Error& e) {
    if (group) group->finish(1);
    std::cerr << "rcdem: error: " << one_line(e.what()) << "\n";
    return 1;
  } catch (const std::exception& e) {
    if (group) group->finish(1);
    std::cerr << "rcdem: internal error: " << one_line(e.what()) << "\n";
    return 3;
  }
  return 0;
}
