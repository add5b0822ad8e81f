#include "rcdem/run/run.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "rcdem/core/build_info.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/core/simd_level.hpp"
#include "rcdem/io/atomic_file.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/run/crack_record.hpp"
#include "rcdem/io/plot_tool.hpp"
#include "rcdem/run/run_manifest.hpp"
#include "rcdem/run/run_output.hpp"
#include "rcdem/config/scenario_checks.hpp"
#include "rcdem/io/specimen_output.hpp"
#include "rcdem/run/run_signals.hpp"
#include "rcdem/run/run_warnings.hpp"

namespace rcdem {

namespace fs = std::filesystem;
using io::Inputs;
using io::iso_now;
using io::Manifest;
using io::read_text;
using io::remove_stale_temporaries;
using io::RunLock;
using io::scenario_inputs;
using io::thread_count;

namespace {

const PlateSettings* find(const Scenario& s, const std::string& name) {
  for (const auto& p : s.plates)
    if (p.name == name) return &p;
  return nullptr;
}

// Issue 28: a state that is no longer finite stops the run, naming the first body that went.
void check_finite(const Simulation& sim, Real load, Real displacement) {
  const Energy& e = sim.ledger();
  if (std::isfinite(load) && std::isfinite(displacement) && e.finite()) return;
  const Bodies& b = sim.bodies();
  std::string where = "no body's position or velocity is";
  for (Index i = 0; i < b.size(); ++i)
    if (!b.position[i].allFinite() || !b.velocity[i].allFinite() ||
        !b.angular_velocity[i].allFinite()) {
      where = fmt::format("body {} ({}) is the first that is not", i,
                          i < sim.specimen().concrete() ? "particle" : "bar cylinder");
      break;
    }
  fail(
      "non-finite state at step {} (t = {:.6g} s): load {} N, displacement {} m, external work "
      "{} J, strain {} J, kinetic {} J, dissipated {} J; {}: the stiffnesses, masses or loading "
      "are outside what "
      "the scenario's time step can integrate",
      sim.steps(), sim.time(), load, displacement, e.external_work, e.strain, e.kinetic,
      e.dissipated(), where);
}

}  // namespace

void validate_run(const Scenario& s) {
  if (s.plates.empty())
    fail("{}: a run needs plates: add at least one [plates.NAME] section with its face",
         s.source.string());
  if (!s.stop.any())
    fail(
        "{}: no stop rule: set stop.displacement, stop.load_drop, stop.post_peak_displacement, "
        "stop.time or stop.steps",
        s.source.string());
  const PlateSettings* control = find(s, s.control_plate);
  if ((s.stop.displacement > 0.0 || s.stop.load_drop > 0.0 ||
       s.stop.post_peak_displacement > 0.0) &&
      !control && s.control_bar.empty())
    fail(
        "{}: stop.displacement, stop.load_drop and stop.post_peak_displacement need "
        "loading.control_plate (or loading.control_bar), the plate (or pulled bar) they refer to",
        config::key_location(
            s, s.stop.displacement > 0.0
                   ? "stop.displacement"
                   : (s.stop.load_drop > 0.0 ? "stop.load_drop" : "stop.post_peak_displacement")));
  // An unglued plate only pushes: moving off its face it never touches the specimen again, and
  // the run would "succeed" with no load (issue 28).
  for (const auto& p : s.plates)
    if (!p.glued && p.velocity * p.side > 0.0)
      fail(
          "{}: plate '{}' moves away from the specimen (velocity {} m/s on the face {}{}, whose "
          "inward normal points to {}{}): an unglued plate only pushes; expected a velocity of the "
          "other sign, or glued = true to pull",
          config::key_location(s, "plates." + p.name + ".velocity"), p.name, p.velocity,
          static_cast<char>('x' + p.axis), p.side < 0 ? '-' : '+', p.side < 0 ? '+' : '-',
          static_cast<char>('x' + p.axis));
  bool moving = false;
  for (const auto& p : s.plates) moving |= p.velocity != 0.0;
  for (const auto& b : s.bars) moving |= b.pull_velocity > 0.0;
  if (!moving && s.stop.time <= 0.0 && s.stop.steps <= 0)
    fail(
        "{}: no plate moves (every velocity is 0), so stop.displacement, stop.load_drop and "
        "stop.post_peak_displacement can never trigger; set a plate's velocity, or stop.time or "
        "stop.steps",
        s.source.string());
  if (s.stop.displacement > 0.0 && control && control->velocity == 0.0 && s.stop.time <= 0.0 &&
      s.stop.steps <= 0)
    fail(
        "{}: stop.displacement can never trigger: the control plate '{}' does not move "
        "(velocity 0)",
        config::key_location(s, "stop.displacement"), control->name);
}

Scenario run_directory_scenario(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail("--resume '{}': no such run directory", dir.string());
  if (!fs::exists(dir / "manifest.json", ec))
    fail("--resume '{}': not a run directory (no manifest.json; generate and calibrate write none)",
         dir.string());
  if (fs::exists(dir / "summary.json", ec))
    fail(
        "--resume '{}': that run has finished (it has summary.json); nothing to resume (rerun it "
        "with -o {} --force to start it again)",
        dir.string(), dir.string());
  const fs::path text_file = dir / "scenario.toml";
  if (!fs::exists(text_file, ec))
    fail("--resume '{}': not a run directory (no scenario.toml)", dir.string());
  std::ifstream in(text_file, std::ios::binary);
  if (!in) fail("--resume '{}': cannot read scenario.toml", dir.string());
  const std::string text = read_text(text_file);
  // Where the scenario came from: its includes are resolved from there, and it keeps its name.
  fs::path file = text_file, given = text_file;
  const auto m = nlohmann::json::parse(read_text(dir / "manifest.json"), nullptr, false);
  if (!m.is_discarded() && m.is_object()) {
    if (m.contains("scenario_file") && m["scenario_file"].is_string())
      file = m["scenario_file"].get<std::string>();
    if (m.contains("scenario") && m["scenario"].is_string())
      given = m["scenario"].get<std::string>();
  }
  Scenario s = parse_scenario(text, file.string());
  s.source = given;
  return s;
}

RunSummary run_scenario(const Scenario& sc, const fs::path& out,
                        const std::function<void(const Simulation&)>& on_step) {
  return run_scenario(sc, out, RunOptions{}, on_step);
}

RunSummary run_scenario(const Scenario& sc, const fs::path& out, const RunOptions& opt,
                        const std::function<void(const Simulation&)>& on_step) {
  validate_run(sc);
  const auto wall_start = std::chrono::steady_clock::now();
  const bool checkpoints = opt.resume || opt.handle_signals || opt.checkpoint_every_steps > 0 ||
                           opt.checkpoint_every_seconds > 0.0;
  RunLock lock(out, checkpoints && !opt.lock_held);
  SignalGuard signals(opt.handle_signals, out / "run.lock", opt.resume);
  const bool quiet = Progress::quiet_default();

  // The manifest, started (or, resuming, continued) before anything else can fail.
  Manifest manifest(out, opt.manifest);
  fs::path scenario_file;
  if (opt.resume) {
    manifest.load_existing();
    const auto& j = manifest.json();
    scenario_file = j.contains("scenario_file") && j["scenario_file"].is_string()
                        ? fs::path(j["scenario_file"].get<std::string>())
                        : out / "scenario.toml";
  } else if (!sc.source.empty()) {
    std::error_code ec;
    scenario_file = fs::absolute(sc.source, ec);
  }
  const Inputs inputs = scenario_inputs(sc.text, scenario_file);
  if (opt.resume && manifest.json().contains("inputs") && manifest.json()["inputs"].is_array()) {
    // Which input changed, if one did (the checkpoint would only say that something did).
    for (const auto& was : manifest.json()["inputs"]) {
      const std::string path = was.value("path", ""), hash = was.value("fnv1a64", "");
      bool found = false;
      for (const auto& now : inputs.list)
        if (now["path"] == path) {
          found = true;
          if (now["fnv1a64"] != hash)
            fail(
                "cannot resume '{}': the scenario input '{}' changed since the run started "
                "(FNV-1a {} then, {} now); restore it, or start a new run",
                out.string(), path, hash, now["fnv1a64"].get<std::string>());
        }
      if (!found)
        fail("cannot resume '{}': the scenario no longer reads '{}' as it did when the run started",
             out.string(), path);
    }
  }
  {
    auto& j = manifest.json();
    const std::string version = build_version(), git = build_git_hash();
    if (!opt.resume) {
      j["manifest_version"] = 1;
      j["scenario"] = sc.source.string();
      j["scenario_file"] = scenario_file.string();
      j["scenario_copy"] = "scenario.toml";
      j["inputs"] = inputs.list;
      j["inputs_hash"] = fmt::format("{:016x}", inputs.hash);
      j["seed"] = sc.generation.seed;
      j["command"] = opt.command;
      j["rcdem_version"] = version;
      j["git_hash"] = git;
      j["build"] = build_flavour();
      j["threads"] = thread_count();
      j["start_time"] = iso_now();
      j["end_time"] = nullptr;
      j["exit_state"] = "running";
      j["steps"] = 0;
      j["time_s"] = 0.0;
      j["wall_seconds"] = 0.0;
      j["last_checkpoint"] = nullptr;
      j["sessions"] = nlohmann::ordered_json::array();
    }
    j["rcdem_version"] = version;
    j["git_hash"] = git;
    j["build"] = build_flavour();
    j["threads"] = thread_count();
    j["exit_state"] = "running";
    j["end_time"] = nullptr;
    j["sessions"].push_back({{"start_time", iso_now()},
                             {"end_time", nullptr},
                             {"rcdem_version", version},
                             {"git_hash", git},
                             {"build", build_flavour()},
                             {"threads", thread_count()},
                             {"command", opt.command},
                             {"resumed_from", nullptr},
                             {"exit_state", "running"}});
    if (!opt.checkpoint_every_text.empty()) {
      j["checkpoint_every"] = opt.checkpoint_every_text;
      j["sessions"].back()["checkpoint_every"] = opt.checkpoint_every_text;
    }
  }
  // A run refused during its set-up leaves no manifest (nor anything else) behind.
  bool manifest_started = opt.resume;
  const auto record_failure = [&](const std::string& what) {
    if (!manifest_started) return;
    auto& j = manifest.json();
    j["exit_state"] = "failed";
    j["error"] = what;
    j["end_time"] = iso_now();
    manifest.session()["exit_state"] = "failed";
    manifest.session()["error"] = what;
    manifest.session()["end_time"] = j["end_time"];
    manifest.write_quietly();
  };
  if (!opt.resume) {
    // --force over an earlier run: its checkpoints must not be resumed into this one.
    io::remove_checkpoints(out);
  } else {
    remove_stale_temporaries(out);
  }

  try {
    std::optional<Simulation> built;
    try {
      built.emplace(sc, build_specimen(sc));
    } catch (const Error& e) {
      rethrow_naming(sc.source.string(), e);
    }
    Simulation& sim = *built;
    // Written only once the set-up has passed every check, so a refused run leaves nothing.
    if (!opt.resume) {
      io::write_file_atomically(out / "scenario.toml", sc.text);
      io::write_particles_vtu(out / "particles_initial.vtu", sim.specimen(), sc.output.binary_vtu);
    }
    manifest.write();
    manifest_started = true;
    if (opt.on_started) opt.on_started();
    if (!quiet)
      fmt::print(stderr,
                 "time step {:.4g} s (stable estimate {:.4g} s, set by {}; safety {}); {} bodies, "
                 "{} contacts, {} local points, {} plate contacts\n",
                 sim.time_step(), sim.stable_time_step(), sim.stable_time_step_limit(),
                 sc.solver.time_step > 0.0 ? sc.solver.time_step / sim.stable_time_step()
                                           : sc.solver.dt_safety,
                 sim.bodies().size(), sim.specimen().contacts.contact_count(),
                 sim.specimen().contacts.point_count(), sim.plate_contacts().size());

    // The test's load and displacement: a control plate's, or a pulled bar's.
    const Plate* control = sim.find_plate(sc.control_plate);
    const PulledBar* pulled = sim.find_pulled_bar(sc.control_bar);
    const auto control_load = [&] {
      return control ? control->load() : pulled ? pulled->load() : 0.0;
    };
    const auto control_displacement = [&] {
      return control ? control->displacement : pulled ? pulled->displacement : 0.0;
    };
    const Real control_speed = control ? std::abs(control->velocity) : pulled ? pulled->speed : 0.0;
    const Real control_ramp = control ? control->ramp_time : pulled ? pulled->ramp_time : 0.0;

    io::History history(sim, sc.control_plate.empty() ? sc.control_bar : sc.control_plate);
    io::SnapshotWriter snapshots(out, sc.output.binary_vtu, sc.output.write_facets);
    io::CrackRecord cracks(sim);
    io::LoopState loop;
    const io::CheckpointParts parts{&sim, &history, &snapshots, &cracks, &loop};
    if (opt.resume) {
      const io::RestoreReport rep = io::restore_latest_checkpoint(out, parts, inputs.hash);
      for (const auto& line : rep.rejected) fmt::print(stderr, "rcdem: warning: {}\n", line);
      const std::string writer = fmt::format("rcdem {} ({})", build_version(), build_git_hash());
      if (rep.header.writer != writer)
        fmt::print(stderr,
                   "rcdem: warning: {} was written by {}, this is {}: the rest of the run may "
                   "differ from an uninterrupted one\n",
                   rep.file.filename().string(), rep.header.writer, writer);
      if (!quiet)
        fmt::print(stderr, "resuming from {} (step {}, t = {:.6g} s)\n", rep.file.string(),
                   rep.header.step, rep.header.time);
      manifest.session()["resumed_from"] = {{"file", rep.file.filename().string()},
                                            {"step", rep.header.step},
                                            {"time_s", rep.header.time}};
      if (!rep.rejected.empty()) manifest.session()["rejected_checkpoints"] = rep.rejected;
      manifest.write();
    }

    // How many steps the run will take, where a rule tells: for the history and snapshot
    // spacing and the progress line.
    Real expected = std::numeric_limits<Real>::infinity();
    if (sc.stop.steps > 0) expected = std::min(expected, static_cast<Real>(sc.stop.steps));
    if (sc.stop.time > 0.0) expected = std::min(expected, sc.stop.time / sim.time_step());
    if (sc.stop.displacement > 0.0 && control_speed > 0.0)
      expected = std::min(
          expected, (sc.stop.displacement / control_speed + 0.5 * control_ramp) / sim.time_step());
    if (!std::isfinite(expected)) expected = 1e5;  // load_drop only: a guess for the spacing
    const auto history_every = std::max<std::int64_t>(
        1, static_cast<std::int64_t>(expected / static_cast<Real>(sc.output.history_rows)));
    const auto snapshot_every =
        sc.output.snapshots > 0
            ? std::max<std::int64_t>(
                  1, static_cast<std::int64_t>(expected / static_cast<Real>(sc.output.snapshots)))
            : std::numeric_limits<std::int64_t>::max();
    if (opt.resume) {
      if (loop.history_every != history_every || loop.snapshot_every != snapshot_every)
        fail(
            "checkpoint of '{}': history every {} and snapshots every {} steps, this run would "
            "use {} and {}: it cannot continue the same run",
            out.string(), loop.history_every, loop.snapshot_every, history_every, snapshot_every);
    } else {
      loop.history_every = history_every;
      loop.snapshot_every = snapshot_every;
      snapshots.write(sim);
      history.record(sim);
    }
    const double wall_before = loop.wall_seconds, loop_before = loop.loop_seconds;
    const std::int64_t first_step = sim.steps();

    RunSummary r;
    r.peak_load = loop.peak_load;
    r.displacement_at_peak = loop.displacement_at_peak;
    r.kinetic_over_strain_at_peak = loop.kinetic_over_strain_at_peak;
    Real peak = loop.peak;
    const bool tty = ::isatty(STDERR_FILENO) != 0;
    auto last_report = std::chrono::steady_clock::now();
    const auto loop_start = last_report;
    auto last_checkpoint = last_report;
    std::int64_t checkpointed_step = opt.resume ? sim.steps() : -1;

    // A checkpoint of the state after the whole of step n (outputs included), and the manifest.
    const auto checkpoint = [&](std::chrono::steady_clock::time_point now) {
      loop.peak = peak;
      loop.peak_load = r.peak_load;
      loop.displacement_at_peak = r.displacement_at_peak;
      loop.kinetic_over_strain_at_peak = r.kinetic_over_strain_at_peak;
      loop.wall_seconds = wall_before + std::chrono::duration<double>(now - wall_start).count();
      loop.loop_seconds = loop_before + std::chrono::duration<double>(now - loop_start).count();
      r.checkpoint = io::write_checkpoint(out, parts, inputs.hash);
      checkpointed_step = sim.steps();
      last_checkpoint = std::chrono::steady_clock::now();
      auto& j = manifest.json();
      j["steps"] = sim.steps();
      j["time_s"] = sim.time();
      j["wall_seconds"] = loop.wall_seconds;
      j["last_checkpoint"] = {{"file", r.checkpoint.filename().string()},
                              {"step", sim.steps()},
                              {"time_s", sim.time()},
                              {"written", iso_now()}};
      manifest.session()["steps_at_last_checkpoint"] = sim.steps();
      manifest.write();
    };
    // Output failures (disk full, directory gone) say where the run can continue from.
    const auto with_resume_hint = [&](const Error& e) {
      if (!checkpoints || checkpointed_step < 0) return Error(e.what());
      return Error(fmt::format(
          "{} (at step {}; the checkpoint of step {} is intact: when the problem is fixed, "
          "continue with: rcdem run --resume {})",
          e.what(), sim.steps(), checkpointed_step, out.string()));
    };

    signals.loop();
    for (;;) {
      Real load = 0.0;
      try {
        sim.step();
        load = control_load();
        check_finite(sim, load, control_displacement());
      } catch (const Error& e) {
        // What the run recorded up to the failure is kept for the diagnosis.
        try {
          history.write(out / "history.csv");
        } catch (const Error&) {
        }
        rethrow_naming(sc.source.string(),
                       Error(fmt::format("{} (history.csv is kept, up to step {})", e.what(),
                                         history.rows() ? history.data().back()[0] : 0.0)));
      }
      if (on_step) on_step(sim);
      if (load > peak) {
        peak = load;
        r.peak_load = load;
        r.displacement_at_peak = control_displacement();
        // The strain energy from the balance of SPEC 11 (W = E_s + E_k + D, kept within 1e-4):
        // summing it over a million local points at every new peak would cost a step's time.
        const Energy& e = sim.ledger();
        const Real strain = e.external_work - e.kinetic - e.dissipated();
        r.kinetic_over_strain_at_peak = strain > 0.0 ? e.kinetic / strain : 0.0;
      }
      const std::int64_t n = sim.steps();
      if (n % history_every == 0) {
        history.record(sim);
        cracks.update(sim, control_displacement(), load);
      }
      if (n % snapshot_every == 0) {
        try {
          snapshots.write(sim);
          history.write(out / "history.csv");
        } catch (const Error& e) {
          throw with_resume_hint(e);
        }
      }
      // Stop rules.
      if (sc.stop.steps > 0 && n >= sc.stop.steps) r.stop_reason = "steps";
      if (sc.stop.time > 0.0 && sim.time() >= sc.stop.time) r.stop_reason = "time";
      if (sc.stop.displacement > 0.0 && std::abs(control_displacement()) >= sc.stop.displacement)
        r.stop_reason = "displacement";
      // After the peak: the load has fallen below the fraction, and the peak is a real one (the
      // specimen has cracked: some local point is fully broken).
      if (sc.stop.load_drop > 0.0 && peak > 0.0 && load < sc.stop.load_drop * peak &&
          sim.ledger().damage > 0.0)
        r.stop_reason = "load_drop";
      // Peak plus a defined post-peak (issue 5): the plate has gone this far past the peak's
      // position, again only once the specimen has cracked.
      if (sc.stop.post_peak_displacement > 0.0 && peak > 0.0 &&
          std::abs(control_displacement()) - std::abs(r.displacement_at_peak) >=
              sc.stop.post_peak_displacement &&
          sim.ledger().damage > 0.0)
        r.stop_reason = "post_peak_displacement";
      const auto now = std::chrono::steady_clock::now();
      if (!quiet && std::chrono::duration<double>(now - last_report).count() > (tty ? 0.5 : 10.0)) {
        last_report = now;
        const double elapsed = std::chrono::duration<double>(now - loop_start).count();
        const double rate = static_cast<double>(n - first_step) / elapsed;
        const double frac = std::min(1.0, static_cast<double>(n) / expected);
        fmt::print(stderr,
                   "{}step {} ({:.1f}%)  {:.0f} steps/s  ETA {:.0f} s  load {:.4g} N  peak "
                   "{:.4g} N{}",
                   tty ? "\r" : "", n, 100.0 * frac, rate,
                   rate > 0 ? std::max(0.0, expected - static_cast<double>(n)) / rate : 0.0, load,
                   peak, tty ? "   " : "\n");
        std::fflush(stderr);
      }
      if (!r.stop_reason.empty()) break;
      const bool due = (opt.checkpoint_every_steps > 0 && n % opt.checkpoint_every_steps == 0) ||
                       (opt.checkpoint_every_seconds > 0.0 &&
                        std::chrono::duration<double>(now - last_checkpoint).count() >=
                            opt.checkpoint_every_seconds);
      if (due) {
        try {
          checkpoint(now);
        } catch (const Error& e) {
          throw with_resume_hint(e);
        }
      }
      if (pending_stop_signal() != 0) {
        // Interrupted: the state after this whole step is saved, with what the run has so far.
        const int sig = pending_stop_signal();
        try {
          if (checkpointed_step != n) checkpoint(now);
          history.write(out / "history.csv");
          cracks.write(out / "broken_points.csv");
        } catch (const Error& e) {
          throw with_resume_hint(e);
        }
        auto& j = manifest.json();
        j["exit_state"] = "interrupted";
        j["end_time"] = iso_now();
        manifest.session()["exit_state"] = "interrupted";
        manifest.session()["signal"] = signal_name(sig);
        manifest.session()["end_time"] = j["end_time"];
        manifest.session()["wall_seconds"] =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
        manifest.write_quietly();
        if (!quiet && tty) fmt::print(stderr, "\n");
        fmt::print(stderr,
                   "rcdem: interrupted by {} at step {} (t = {:.6g} s); checkpoint {} written; "
                   "resume with: rcdem run --resume {}\n",
                   signal_name(sig), n, sim.time(), r.checkpoint.filename().string(), out.string());
        r.stop_reason = "interrupted";
        r.signal = sig;
        r.steps = n;
        r.time = sim.time();
        r.energy = sim.energy();
        return r;
      }
    }
    if (!quiet && tty) fmt::print(stderr, "\n");
    if (history.rows() == 0 || history.data().back()[0] != static_cast<double>(sim.steps()))
      history.record(sim);
    cracks.update(sim, control_displacement(), control_load());
    try {
      snapshots.write(sim);
      history.write(out / "history.csv");
      cracks.write(out / "broken_points.csv");
    } catch (const Error& e) {
      throw with_resume_hint(e);
    }

    r.steps = sim.steps();
    r.time = sim.time();
    r.energy = sim.energy();
    const auto end = std::chrono::steady_clock::now();
    const double wall = wall_before + std::chrono::duration<double>(end - wall_start).count();
    auto& j = r.json;
    j["scenario"] = sc.source.string();
    j["stop_reason"] = r.stop_reason;
    j["steps"] = r.steps;
    j["time_s"] = r.time;
    j["time_step_s"] = sim.time_step();
    j["stable_time_step_s"] = sim.stable_time_step();
    j["stable_time_step_set_by"] = sim.stable_time_step_limit();
    const MassScalingPlan& ms = sim.mass_scaling();
    j["selective_mass_scaling"] = {{"added_mass_limit", sc.solver.added_mass_limit},
                                   {"bodies_scaled", ms.bodies_scaled},
                                   {"largest_factor", ms.largest_factor},
                                   {"added_mass_fraction", ms.added_fraction()},
                                   {"unscaled_stable_time_step_s", ms.unscaled_step}};
    j["control"] = sc.control_plate.empty() ? sc.control_bar : sc.control_plate;
    j["peak_load_N"] = r.peak_load;
    j["displacement_at_peak_m"] = r.displacement_at_peak;
    j["kinetic_over_strain_at_peak"] = r.kinetic_over_strain_at_peak;
    const Energy& e = r.energy;
    j["energy"] = {{"external_work_J", e.external_work},
                   {"strain_J", e.strain},
                   {"kinetic_J", e.kinetic},
                   {"dissipated_damage_J", e.damage},
                   {"dissipated_friction_J", e.friction},
                   {"dissipated_damping_J", e.damping},
                   {"dissipated_plastic_J", e.plastic},
                   {"balance_error", e.balance_error()}};
    j["damaged_points"] = sim.damaged_points();
    j["broken_points"] = sim.broken_points();
    j["first_cracking"] = cracks.first_cracking();
    j["local_points"] = sim.specimen().contacts.point_count();
    j["specimen"] = io::specimen_summary(sc, sim.specimen());
    j["gauges"] = history.gauges().summary();
    RunOutcome outcome;
    set_expectation(sc, outcome);
    outcome.peak_load = r.peak_load;
    outcome.control_travel = std::abs(control_displacement());
    outcome.balance_error = e.balance_error();
    j["warnings"] = suspicious_run_warnings(outcome);
    for (const auto& w : j["warnings"])
      fmt::print(stderr, "rcdem: warning: {}\n", w.get<std::string>());
    // Wall-clock figures cover every session up to the state each handed on (a resumed run:
    // up to its checkpoint), so they may differ between otherwise identical runs.
    const double loop_s = loop_before + std::chrono::duration<double>(end - loop_start).count();
    j["loop_seconds"] = loop_s;
    j["steps_per_second"] = loop_s > 0.0 ? static_cast<double>(r.steps) / loop_s : 0.0;
    j["seconds"] = wall;
    j["rcdem"] = {{"version", build_version()},
                  {"git_hash", build_git_hash()},
                  {"build", build_flavour()},
                  {"simd", simd_level_name(simd_level())}};
    io::write_file_atomically(out / "summary.json", j.dump(2) + "\n");
    io::run_plot_tool("plot_history.py", out);  // load_displacement.png
    r.history_columns = history.columns();
    r.history_rows = history.data();
    {
      auto& m = manifest.json();
      m["exit_state"] = "finished";
      m["stop_reason"] = r.stop_reason;
      m["end_time"] = iso_now();
      m["steps"] = r.steps;
      m["time_s"] = r.time;
      m["wall_seconds"] = wall;
      manifest.session()["exit_state"] = "finished";
      manifest.session()["end_time"] = m["end_time"];
      manifest.session()["wall_seconds"] = std::chrono::duration<double>(end - wall_start).count();
      if (checkpoints && !opt.keep_checkpoints) {
        io::remove_checkpoints(out);
        m["last_checkpoint"] = nullptr;
      }
      manifest.write_quietly();
    }
    if (!quiet)
      fmt::print(stderr,
                 "stopped by {} after {} steps (t = {:.4g} s); peak load {:.6g} N at {:.4g} m; "
                 "energy balance: external work {:.6g} J = strain {:.6g} + kinetic {:.4g} + "
                 "dissipated {:.6g} J (error {:.3f}%)\n",
                 r.stop_reason, r.steps, r.time, r.peak_load, r.displacement_at_peak,
                 e.external_work, e.strain, e.kinetic, e.dissipated(), 100.0 * e.balance_error());
    return r;
  } catch (const Error& e) {
    record_failure(e.what());
    throw;
  } catch (const std::exception& e) {
    record_failure(std::string("internal error: ") + e.what());
    throw;
  }
}

}  // namespace rcdem
