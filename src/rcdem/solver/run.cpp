#include "rcdem/solver/run.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/io/atomic_file.hpp"
#include "rcdem/io/crack_record.hpp"
#include "rcdem/io/plot_tool.hpp"
#include "rcdem/io/run_output.hpp"
#include "rcdem/io/specimen_output.hpp"

namespace rcdem {

namespace {

std::string at(const Scenario& s, const std::string& key) {
  const auto it = s.key_line.find(key);
  return it == s.key_line.end() ? s.source.string()
                                : fmt::format("{}:{}", s.source.string(), it->second);
}

const PlateSettings* find(const Scenario& s, const std::string& name) {
  for (const auto& p : s.plates)
    if (p.name == name) return &p;
  return nullptr;
}

}  // namespace

void validate_run(const Scenario& s) {
  if (s.plates.empty())
    fail("{}: a run needs plates: add at least one [plates.NAME] section with its face",
         s.source.string());
  if (!s.stop.any())
    fail("{}: no stop rule: set stop.displacement, stop.load_drop, stop.time or stop.steps",
         s.source.string());
  const PlateSettings* control = find(s, s.control_plate);
  if ((s.stop.displacement > 0.0 || s.stop.load_drop > 0.0) && !control && s.control_bar.empty())
    fail(
        "{}: stop.displacement and stop.load_drop need loading.control_plate (or "
        "loading.control_bar), the plate (or pulled bar) they refer to",
        at(s, s.stop.displacement > 0.0 ? "stop.displacement" : "stop.load_drop"));
  bool moving = false;
  for (const auto& p : s.plates) moving |= p.velocity != 0.0;
  for (const auto& b : s.bars) moving |= b.pull_velocity > 0.0;
  if (!moving && s.stop.time <= 0.0 && s.stop.steps <= 0)
    fail(
        "{}: no plate moves (every velocity is 0), so stop.displacement and stop.load_drop "
        "can never trigger; set a plate's velocity, or stop.time or stop.steps",
        s.source.string());
  if (s.stop.displacement > 0.0 && control && control->velocity == 0.0 && s.stop.time <= 0.0 &&
      s.stop.steps <= 0)
    fail(
        "{}: stop.displacement can never trigger: the control plate '{}' does not move "
        "(velocity 0)",
        at(s, "stop.displacement"), control->name);
}

RunSummary run_scenario(const Scenario& sc, const std::filesystem::path& out,
                        const std::function<void(const Simulation&)>& on_step) {
  validate_run(sc);
  const auto wall_start = std::chrono::steady_clock::now();
  Simulation sim(sc, build_specimen(sc));
  // Written only once the set-up has passed every check, so a refused run leaves nothing.
  io::write_file_atomically(out / "scenario.toml", sc.text);
  io::write_particles_vtu(out / "particles_initial.vtu", sim.specimen(), sc.output.binary_vtu);
  const bool quiet = Progress::quiet_default();
  if (!quiet)
    fmt::print(stderr,
               "time step {:.4g} s (stable estimate {:.4g} s, set by {}; safety {}); {} bodies, "
               "{} contacts, {} local points, {} plate contacts\n",
               sim.time_step(), sim.stable_time_step(), sim.stable_time_step_limit(),
               sc.solver.time_step > 0.0 ? sc.solver.time_step / sim.stable_time_step()
                                         : sc.solver.dt_safety,
               sim.bodies().size(), sim.specimen().contacts.contact_count(),
               sim.specimen().contacts.point_count(), sim.plate_contacts().size());

  // How many steps the run will take, where a rule tells: for the history and snapshot spacing
  // and the progress line.
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

  io::History history(sim, sc.control_plate.empty() ? sc.control_bar : sc.control_plate);
  io::SnapshotWriter snapshots(out, sc.output.binary_vtu, sc.output.write_facets);
  io::CrackRecord cracks(sim);
  snapshots.write(sim);
  history.record(sim);

  RunSummary r;
  Real peak = 0.0;
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  auto last_report = std::chrono::steady_clock::now();
  const auto loop_start = last_report;
  for (;;) {
    sim.step();
    if (on_step) on_step(sim);
    const Real load = control_load();
    if (load > peak) {
      peak = load;
      r.peak_load = load;
      r.displacement_at_peak = control_displacement();
      const Real strain = sim.energy().strain;
      r.kinetic_over_strain_at_peak = strain > 0.0 ? sim.energy().kinetic / strain : 0.0;
    }
    const std::int64_t n = sim.steps();
    if (n % history_every == 0) {
      history.record(sim);
      cracks.update(sim, control_displacement(), load);
    }
    if (n % snapshot_every == 0) {
      snapshots.write(sim);
      history.write(out / "history.csv");
    }
    // Stop rules.
    if (sc.stop.steps > 0 && n >= sc.stop.steps) r.stop_reason = "steps";
    if (sc.stop.time > 0.0 && sim.time() >= sc.stop.time) r.stop_reason = "time";
    if (sc.stop.displacement > 0.0 && std::abs(control_displacement()) >= sc.stop.displacement)
      r.stop_reason = "displacement";
    // After the peak: the load has fallen below the fraction, and the peak is a real one (the
    // specimen has cracked: some local point is fully broken).
    if (sc.stop.load_drop > 0.0 && peak > 0.0 && load < sc.stop.load_drop * peak &&
        sim.energy().damage > 0.0)
      r.stop_reason = "load_drop";
    const auto now = std::chrono::steady_clock::now();
    if (!quiet && std::chrono::duration<double>(now - last_report).count() > (tty ? 0.5 : 10.0)) {
      last_report = now;
      const double elapsed = std::chrono::duration<double>(now - loop_start).count();
      const double rate = static_cast<double>(n) / elapsed;
      const double frac = std::min(1.0, static_cast<double>(n) / expected);
      fmt::print(stderr,
                 "{}step {} ({:.1f}%)  {:.0f} steps/s  ETA {:.0f} s  load {:.4g} N  peak "
                 "{:.4g} N{}",
                 tty ? "\r" : "", n, 100.0 * frac, rate,
                 rate > 0 ? (expected - static_cast<double>(n)) / rate : 0.0, load, peak,
                 tty ? "   " : "\n");
      std::fflush(stderr);
    }
    if (!r.stop_reason.empty()) break;
  }
  if (!quiet && tty) fmt::print(stderr, "\n");
  if (history.rows() == 0 || history.data().back()[0] != static_cast<double>(sim.steps()))
    history.record(sim);
  cracks.update(sim, control_displacement(), control_load());
  snapshots.write(sim);
  history.write(out / "history.csv");
  cracks.write(out / "broken_points.csv");

  r.steps = sim.steps();
  r.time = sim.time();
  r.energy = sim.energy();
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  auto& j = r.json;
  j["scenario"] = sc.source.string();
  j["stop_reason"] = r.stop_reason;
  j["steps"] = r.steps;
  j["time_s"] = r.time;
  j["time_step_s"] = sim.time_step();
  j["stable_time_step_s"] = sim.stable_time_step();
  j["stable_time_step_set_by"] = sim.stable_time_step_limit();
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
  const double loop =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
  j["loop_seconds"] = loop;
  j["steps_per_second"] = loop > 0.0 ? static_cast<double>(r.steps) / loop : 0.0;
  j["seconds"] = wall;
  io::write_file_atomically(out / "summary.json", j.dump(2) + "\n");
  io::run_plot_tool("plot_history.py", out);  // load_displacement.png
  r.history_columns = history.columns();
  r.history_rows = history.data();
  if (!quiet)
    fmt::print(stderr,
               "stopped by {} after {} steps (t = {:.4g} s); peak load {:.6g} N at {:.4g} m; "
               "energy balance: external work {:.6g} J = strain {:.6g} + kinetic {:.4g} + "
               "dissipated {:.6g} J (error {:.3f}%)\n",
               r.stop_reason, r.steps, r.time, r.peak_load, r.displacement_at_peak, e.external_work,
               e.strain, e.kinetic, e.dissipated(), 100.0 * e.balance_error());
  return r;
}

}  // namespace rcdem
