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
#include <numeric>
#include <optional>
#include <sstream>
#include <utility>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "rcdem/config/scenario_checks.hpp"
#include "rcdem/core/build_info.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/core/simd_level.hpp"
#include "rcdem/core/thread_count_tuner.hpp"
#include "rcdem/io/atomic_file.hpp"
#include "rcdem/io/plot_tool.hpp"
#include "rcdem/io/specimen_output.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/run/crack_record.hpp"
#include "rcdem/run/distributed_run.hpp"
#include "rcdem/run/observers.hpp"
#include "rcdem/run/run_manifest.hpp"
#include "rcdem/run/run_output.hpp"
#include "rcdem/run/run_session.hpp"
#include "rcdem/run/run_signals.hpp"
#include "rcdem/run/run_warnings.hpp"
#include "rcdem/solver/test_measures.hpp"

namespace rcdem {

namespace fs = std::filesystem;
using io::iso_now;
using io::read_text;

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
  if (!s.stop.any() && !has_program(s))
    fail(
        "{}: no stop rule: set stop.displacement, stop.load_drop, stop.post_peak_displacement, "
        "stop.time or stop.steps, or give a plate or pulled bar a program (its end stops the run)",
        s.source.string());
  const std::vector<std::string> load_plates = s.load_plates();
  const PlateSettings* control = load_plates.size() == 1 ? find(s, load_plates[0]) : nullptr;
  if ((s.stop.displacement > 0.0 || s.stop.load_drop > 0.0 ||
       s.stop.post_peak_displacement > 0.0) &&
      load_plates.empty() && s.control_bar.empty())
    fail(
        "{}: stop.displacement, stop.load_drop and stop.post_peak_displacement need "
        "loading.control_plate(s) (or loading.control_bar), the plates (or pulled bar) they refer "
        "to",
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
  for (const auto& p : s.plates) moving |= p.velocity != 0.0 || !p.program.empty();
  for (const auto& b : s.bars) moving |= b.pulled();
  if (!moving && s.stop.time <= 0.0 && s.stop.steps <= 0)
    fail(
        "{}: no plate moves (every velocity is 0), so stop.displacement, stop.load_drop and "
        "stop.post_peak_displacement can never trigger; set a plate's velocity, or stop.time or "
        "stop.steps",
        s.source.string());
  if (s.stop.displacement > 0.0 && control && control->velocity == 0.0 && s.stop.time <= 0.0 &&
      s.stop.steps <= 0 && s.displacement_gauge.empty())
    fail(
        "{}: stop.displacement can never trigger: the control plate '{}' does not move "
        "(velocity 0)",
        config::key_location(s, "stop.displacement"), control->name);
}

bool complete_finished_run(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir / "summary.json", ec)) return false;
  const io::RunLock lock(dir, true);
  auto m = nlohmann::ordered_json::parse(read_text(dir / "manifest.json"), nullptr, false);
  if (m.is_discarded() || !m.is_object() || m.value("exit_state", "") != "running") return false;
  const auto s = nlohmann::json::parse(read_text(dir / "summary.json"), nullptr, false);
  if (s.is_discarded() || !s.is_object() || !s.contains("steps") || !s["steps"].is_number())
    fail(
        "--resume '{}': summary.json is damaged and the manifest says the run never finished; "
        "start the run again (-o {} --force)",
        dir.string(), dir.string());
  const std::string note =
      "completed by --resume: the run wrote summary.json but stopped before its manifest's last "
      "update";
  const std::string now = io::iso_now();
  m["exit_state"] = "finished";
  m["end_time"] = now;
  m["steps"] = s["steps"];
  if (s.contains("time_s")) m["time_s"] = s["time_s"];
  m["note"] = note;
  if (m.contains("sessions") && m["sessions"].is_array() && !m["sessions"].empty()) {
    auto& last = m["sessions"].back();
    last["exit_state"] = "finished";
    last["end_time"] = now;
    last["note"] = note;
  }
  io::remove_checkpoints(dir);
  m["last_checkpoint"] = nullptr;
  io::write_file_atomically(dir / "manifest.json", m.dump(2) + "\n");
  if (!fs::exists(dir / "load_displacement.png", ec)) io::run_plot_tool("plot_history.py", dir);
  return true;
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

namespace {

// Snapshots expected to take more than this (bytes) are announced at the set-up.
constexpr double kLargeOutputBytes = 1e9;

// summary.json's exchange_seconds_by_rank: one object per rank, its seconds by kind.
nlohmann::ordered_json exchange_json(const std::vector<ExchangeSeconds>& by_rank) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const ExchangeSeconds& rank : by_rank) {
    nlohmann::ordered_json one;
    for (std::size_t k = 0; k < rank.size(); ++k) one[kExchangeKindNames[k]] = rank[k];
    all.push_back(one);
  }
  return all;
}

// How many steps the run will take, where a rule tells: for the history and snapshot spacing and
// the progress line.
Real expected_steps(const Scenario& sc, const Simulation& sim, const TestMeasures& control) {
  Real expected = std::numeric_limits<Real>::infinity();
  if (sc.stop.steps > 0) expected = std::min(expected, static_cast<Real>(sc.stop.steps));
  if (sc.stop.time > 0.0) expected = std::min(expected, sc.stop.time / sim.time_step());
  if (sc.stop.displacement > 0.0 && control.speed() > 0.0)
    expected = std::min(expected, (sc.stop.displacement / control.speed() + 0.5 * control.ramp()) /
                                      sim.time_step());
  return std::isfinite(expected) ? expected : 1e5;  // load_drop only: a guess for the spacing
}

std::int64_t spacing(Real expected, std::int64_t count) {
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(expected / static_cast<Real>(count)));
}

void print_set_up(const Scenario& sc, const Simulation& sim) {
  fmt::print(stderr,
             "time step {:.4g} s (stable estimate {:.4g} s, set by {}; safety {}); {} bodies, "
             "{} contacts, {} local points, {} plate contacts\n",
             sim.time_step(), sim.stable_time_step(), sim.stable_time_step_limit(),
             sc.solver.time_step > 0.0 ? sc.solver.time_step / sim.stable_time_step()
                                       : sc.solver.dt_safety,
             sim.bodies().size(), sim.specimen().contacts.contact_count(),
             sim.specimen().contacts.point_count(), sim.plate_contacts().size());
}

// One run's loop over steps and what it writes: the observers (peak, history and crack record,
// snapshots, progress), the stop rules, checkpoints and signals, and the summary at the end.
class RunLoop {
 public:
  RunLoop(const Scenario& sc, const fs::path& out, const RunOptions& opt, RunSession& session,
          Simulation& sim, StepThreads& threads);
  // Steps until a stop rule triggers (true) or a signal interrupts (false).
  bool run(const std::function<void(const Simulation&)>& on_step);
  RunSummary finish();
  RunSummary interrupted();

 private:
  void restore();
  void check_spacing_or_start();
  // The load and the test's displacement after the step (a gauge's is read once).
  std::pair<Real, Real> step_once();
  void checkpoint(std::chrono::steady_clock::time_point now);
  bool checkpoint_due(std::int64_t n, std::chrono::steady_clock::time_point now) const;
  RunDecision decide(std::int64_t step);
  Error with_resume_hint(const Error& e) const;
  void write_final_outputs();
  nlohmann::ordered_json summary_json(const RunSummary& r, double wall, double loop_s);
  void finish_manifest(const RunSummary& r, double wall, std::chrono::steady_clock::time_point end);
  RunSummary partial_summary() const;
  void warn_output_volume() const;

  const Scenario& sc_;
  const fs::path out_;
  const RunOptions& opt_;
  RunSession& session_;
  Simulation& sim_;
  StepThreads& threads_;
  const TestMeasures control_;
  io::History history_;
  io::SnapshotWriter snapshots_;
  io::CrackRecord cracks_;
  io::LoopState loop_;
  const io::CheckpointParts parts_;
  Real expected_ = 0.0;
  double wall_before_ = 0.0, loop_before_ = 0.0;
  // The loop's end: the final files (a last snapshot, history.csv, broken_points.csv) are the
  // run's output, not its loop (summary.json's loop_seconds).
  std::chrono::steady_clock::time_point loop_start_, loop_end_, last_checkpoint_;
  // A distributed run's exchange times inside this session's loop, by rank and kind: the set-up's
  // waits for the slowest rank's generation are not the step's cost.
  std::vector<ExchangeSeconds> exchange_by_rank_;
  std::int64_t checkpointed_step_ = -1;
  fs::path last_checkpoint_file_;
  std::string stop_reason_;
  int signal_ = 0;
};

RunLoop::RunLoop(const Scenario& sc, const fs::path& out, const RunOptions& opt,
                 RunSession& session, Simulation& sim, StepThreads& threads)
    : sc_(sc),
      out_(out),
      opt_(opt),
      session_(session),
      sim_(sim),
      threads_(threads),
      control_(sim, sc),
      history_(sim, sc),
      snapshots_(out, sc.output.binary_vtu, sc.output.write_facets),
      cracks_(sim),
      parts_{&sim, &history_, &snapshots_, &cracks_, &loop_} {
  if (opt.resume) restore();
  expected_ = expected_steps(sc, sim, control_);
  check_spacing_or_start();
  wall_before_ = loop_.wall_seconds;
  loop_before_ = loop_.loop_seconds;
  checkpointed_step_ = opt.resume ? sim.steps() : -1;
}

void RunLoop::restore() {
  const io::RestoreReport rep = io::restore_latest_checkpoint(out_, parts_, session_.inputs().hash);
  if (opt_.ranks) opt_.ranks->restored(sim_, rep.file.string(), session_.inputs().hash);
  for (const auto& line : rep.rejected) fmt::print(stderr, "rcdem: warning: {}\n", line);
  const std::string writer = fmt::format("rcdem {} ({})", build_version(), build_git_hash());
  if (rep.header.writer != writer)
    fmt::print(stderr,
               "rcdem: warning: {} was written by {}, this is {}: the rest of the run may differ "
               "from an uninterrupted one\n",
               rep.file.filename().string(), rep.header.writer, writer);
  if (!Progress::quiet_default())
    fmt::print(stderr, "resuming from {} (step {}, t = {:.6g} s)\n", rep.file.string(),
               rep.header.step, rep.header.time);
  io::Manifest& manifest = session_.manifest();
  manifest.session()["resumed_from"] = {{"file", rep.file.filename().string()},
                                        {"step", rep.header.step},
                                        {"time_s", rep.header.time}};
  if (!rep.rejected.empty()) manifest.session()["rejected_checkpoints"] = rep.rejected;
  manifest.write();
}

// A resumed run must keep its output spacing; a new one writes its first rows.
void RunLoop::check_spacing_or_start() {
  const auto history_every = spacing(expected_, sc_.output.history_rows);
  const auto snapshot_every = sc_.output.snapshots > 0 ? spacing(expected_, sc_.output.snapshots)
                                                       : std::numeric_limits<std::int64_t>::max();
  if (opt_.resume) {
    if (loop_.history_every != history_every || loop_.snapshot_every != snapshot_every)
      fail(
          "checkpoint of '{}': history every {} and snapshots every {} steps, this run would use "
          "{} and {}: it cannot continue the same run",
          out_.string(), loop_.history_every, loop_.snapshot_every, history_every, snapshot_every);
    return;
  }
  loop_.history_every = history_every;
  loop_.snapshot_every = snapshot_every;
  snapshots_.write(sim_);
  history_.record(sim_);
  warn_output_volume();
}

// The outputs' volume from the first snapshot's size and the expected count: said at the set-up
// when it is large (over 1 GB or a fifth of the disk's free space), or when more snapshots were
// asked for than the run has steps, so that a mistyped output.snapshots does not silently fill a
// disk.
void RunLoop::warn_output_volume() const {
  std::error_code ec;
  double first = 0.0;
  for (const auto& e : fs::directory_iterator(out_ / "snapshots", ec))
    first += static_cast<double>(e.file_size(ec));
  const double count = 1.0 + std::floor(expected_ / static_cast<double>(loop_.snapshot_every));
  const double bytes = first * count;
  const fs::space_info space = fs::space(out_, ec);
  const double free =
      ec ? std::numeric_limits<double>::infinity() : static_cast<double>(space.available);
  const bool every_step = static_cast<double>(sc_.output.snapshots) > expected_;
  if (bytes < kLargeOutputBytes && bytes < 0.2 * free && !every_step) return;
  std::string why = every_step
                        ? fmt::format("; output.snapshots = {} is more than the run's {:.0f} steps",
                                      sc_.output.snapshots, expected_)
                        : fmt::format("; output.snapshots = {}", sc_.output.snapshots);
  if (bytes >= 0.2 * free) why += fmt::format("; {:.3g} GB are free on its disk", free / 1e9);
  fmt::print(stderr,
             "rcdem: warning: the snapshots will take about {:.3g} GB ({:.0f} snapshots of {:.3g} "
             "MB each{}); lower output.snapshots, or stop the run\n",
             bytes / 1e9, count, first / 1e6, why);
}

// One step and the control's load after it; a failure keeps what the run recorded so far.
std::pair<Real, Real> RunLoop::step_once() {
  try {
    threads_.step([this] { sim_.step(); });
    const Real load = control_.load(), displacement = control_.displacement();
    check_finite(sim_, load, displacement);
    return {load, displacement};
  } catch (const Error& e) {
    try {
      history_.write(out_ / "history.csv");
    } catch (const Error&) {
    }
    rethrow_naming(sc_.source.string(),
                   Error(fmt::format("{} (history.csv is kept, up to step {})", e.what(),
                                     history_.rows() ? history_.data().back()[0] : 0.0)));
  }
}

bool RunLoop::run(const std::function<void(const Simulation&)>& on_step) {
  PeakTracker peak(loop_);
  std::vector<RunObserver*> observers{&peak};
  HistoryRecorder rows(Trigger::every(loop_.history_every), history_, cracks_);
  sim_.keep_strain_energy_every(loop_.history_every);  // each row's strain energy, from its step
  SnapshotRecorder snapshots(Trigger::every(loop_.snapshot_every), snapshots_, history_, out_);
  observers.push_back(&rows);
  observers.push_back(&snapshots);
  ProgressLine progress(expected_, peak);
  const auto rules = stop_rules(sc_, peak);
  loop_start_ = last_checkpoint_ = std::chrono::steady_clock::now();
  if (const RankExchange* x = sim_.exchange()) x->reset_seconds();
  session_.signals().loop();
  for (;;) {
    const auto [load, displacement] = step_once();
    if (on_step) on_step(sim_);
    const StepView view{sim_, sim_.steps(), load, displacement};
    try {
      for (RunObserver* o : observers)
        if (o->trigger()(view.step)) o->act(view);
    } catch (const Error& e) {
      throw with_resume_hint(e);
    }
    for (const auto& rule : rules)
      if (rule->triggered(view)) stop_reason_ = rule->reason();
    // After the stop rules, so that the last step's line is printed before the loop ends.
    if (progress.trigger()(view.step)) progress.act(view);
    if (!stop_reason_.empty()) break;
    const RunDecision decision = decide(view.step);
    if (decision == RunDecision::Stop || decision == RunDecision::Until) {
      stop_reason_ = decision == RunDecision::Stop ? "callback" : "until";
      break;
    }
    const auto now = std::chrono::steady_clock::now();
    if (checkpoint_due(view.step, now)) checkpoint(now);
    if ((signal_ = take_stop_signal()) != 0 || decision == RunDecision::Interrupt) {
      // Interrupted: the state after this whole step is saved, with what the run has so far.
      if (checkpointed_step_ != view.step) checkpoint(now);
      progress.close();
      return false;
    }
  }
  loop_end_ = std::chrono::steady_clock::now();
  if (sim_.exchange()) exchange_by_rank_ = sim_.exchange_seconds_by_rank();
  progress.close();
  return true;
}

RunDecision RunLoop::decide(std::int64_t step) {
  if (!opt_.decide || step % opt_.decide_every != 0) return RunDecision::Continue;
  return opt_.decide(sim_);
}

bool RunLoop::checkpoint_due(std::int64_t n, std::chrono::steady_clock::time_point now) const {
  return (opt_.checkpoint_every_steps > 0 && n % opt_.checkpoint_every_steps == 0) ||
         (opt_.checkpoint_every_seconds > 0.0 &&
          std::chrono::duration<double>(now - last_checkpoint_).count() >=
              opt_.checkpoint_every_seconds);
}

// A checkpoint of the state after the whole of the last step (outputs included), and the manifest.
void RunLoop::checkpoint(std::chrono::steady_clock::time_point now) {
  try {
    loop_.wall_seconds =
        wall_before_ + std::chrono::duration<double>(now - session_.wall_start()).count();
    loop_.loop_seconds = loop_before_ + std::chrono::duration<double>(now - loop_start_).count();
    last_checkpoint_file_ = io::write_checkpoint(out_, parts_, session_.inputs().hash);
    checkpointed_step_ = sim_.steps();
    last_checkpoint_ = std::chrono::steady_clock::now();
    io::Manifest& manifest = session_.manifest();
    auto& j = manifest.json();
    j["steps"] = sim_.steps();
    j["time_s"] = sim_.time();
    j["wall_seconds"] = loop_.wall_seconds;
    j["last_checkpoint"] = {{"file", last_checkpoint_file_.filename().string()},
                            {"step", sim_.steps()},
                            {"time_s", sim_.time()},
                            {"written", iso_now()}};
    manifest.session()["steps_at_last_checkpoint"] = sim_.steps();
    manifest.write();
  } catch (const Error& e) {
    throw with_resume_hint(e);
  }
}

// Output failures (disk full, directory gone) say where the run can continue from.
Error RunLoop::with_resume_hint(const Error& e) const {
  if (!session_.checkpoints() || checkpointed_step_ < 0) return Error(e.what());
  return Error(fmt::format(
      "{} (at step {}; the checkpoint of step {} is intact: when the problem is fixed, continue "
      "with: rcdem run --resume {})",
      e.what(), sim_.steps(), checkpointed_step_, out_.string()));
}

RunSummary RunLoop::partial_summary() const {
  RunSummary r;
  r.stop_reason = stop_reason_;
  r.peak_load = loop_.peak;
  r.displacement_at_peak = loop_.displacement_at_peak;
  r.kinetic_over_strain_at_peak = loop_.kinetic_over_strain_at_peak;
  r.steps = sim_.steps();
  r.time = sim_.time();
  r.energy = sim_.energy();
  r.checkpoint = last_checkpoint_file_;
  return r;
}

RunSummary RunLoop::interrupted() {
  try {
    history_.write(out_ / "history.csv");
    cracks_.write(out_ / "broken_points.csv");
  } catch (const Error& e) {
    throw with_resume_hint(e);
  }
  auto& session = session_.end("interrupted");
  const std::string by = signal_ != 0 ? std::string(signal_name(signal_)) : "the caller's callback";
  session["signal"] = signal_ != 0 ? by : "none (" + by + ")";
  session["wall_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - session_.wall_start())
          .count();
  session_.manifest().write_quietly();
  fmt::print(stderr,
             "rcdem: interrupted by {} at step {} (t = {:.6g} s); checkpoint {} written; resume "
             "with: rcdem run --resume {}\n",
             by, sim_.steps(), sim_.time(), last_checkpoint_file_.filename().string(),
             out_.string());
  RunSummary r = partial_summary();
  r.stop_reason = "interrupted";
  r.signal = signal_;
  return r;
}

void RunLoop::write_final_outputs() {
  if (history_.rows() == 0 || history_.data().back()[0] != static_cast<double>(sim_.steps()))
    history_.record(sim_);
  cracks_.update(sim_, control_.displacement(), control_.load());
  try {
    snapshots_.write(sim_);
    history_.write(out_ / "history.csv");
    cracks_.write(out_ / "broken_points.csv");
  } catch (const Error& e) {
    throw with_resume_hint(e);
  }
}

nlohmann::ordered_json RunLoop::summary_json(const RunSummary& r, double wall, double loop_s) {
  nlohmann::ordered_json j;
  j["scenario"] = sc_.source.string();
  j["stop_reason"] = r.stop_reason;
  j["steps"] = r.steps;
  j["time_s"] = r.time;
  j["time_step_s"] = sim_.time_step();
  j["stable_time_step_s"] = sim_.stable_time_step();
  j["stable_time_step_set_by"] = sim_.stable_time_step_limit();
  const MassScalingPlan& ms = sim_.mass_scaling();
  j["selective_mass_scaling"] = {{"added_mass_limit", sc_.solver.added_mass_limit},
                                 {"bodies_scaled", ms.bodies_scaled},
                                 {"largest_factor", ms.largest_factor},
                                 {"added_mass_fraction", ms.added_fraction()},
                                 {"unscaled_stable_time_step_s", ms.unscaled_step}};
  j["control"] = sc_.control_name();
  j["displacement_column"] = history_.displacement_column();
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
  j["damaged_points"] = sim_.damaged_points();
  j["broken_points"] = sim_.broken_points();
  j["first_cracking"] = cracks_.first_cracking();
  j["local_points"] = sim_.specimen().contacts.point_count();
  j["specimen"] = io::specimen_summary(sc_, sim_.specimen());
  j["gauges"] = history_.gauges().summary();
  RunOutcome outcome;
  set_expectation(sc_, outcome);
  outcome.peak_load = r.peak_load;
  outcome.control_travel = std::abs(control_.control_displacement());
  outcome.balance_error = e.balance_error();
  j["warnings"] = suspicious_run_warnings(outcome);
  for (const auto& w : j["warnings"])
    fmt::print(stderr, "rcdem: warning: {}\n", w.get<std::string>());
  // Wall-clock figures cover every session up to the state each handed on (a resumed run: up to
  // its checkpoint), so they may differ between otherwise identical runs.
  j["loop_seconds"] = loop_s;
  j["steps_per_second"] = loop_s > 0.0 ? static_cast<double>(r.steps) / loop_s : 0.0;
  j["seconds"] = wall;
  const ThreadRecord t = threads_.record();
  j["step_seconds"] = t.step_seconds;
  j["threads"] = {{"tuned", t.tuned},
                  {"max", t.max},
                  {"last", t.last},
                  {"mean", t.mean},
                  {"changes", t.changes}};
  if (const RankExchange* x = sim_.exchange())  // a distributed run (docs/parallel.md)
    j["distributed"] = {
        {"ranks", x->comm().size()},
        {"rank_0_exchange_seconds",
         exchange_by_rank_.empty()
             ? 0.0
             : std::accumulate(exchange_by_rank_[0].begin(), exchange_by_rank_[0].end(), 0.0)},
        {"exchange_seconds_by_rank", exchange_json(exchange_by_rank_)},
        {"rank_0_evaluated_points", x->decomposition().evaluated_points(sim_.specimen().contacts)}};
  j["rcdem"] = {{"version", build_version()},
                {"git_hash", build_git_hash()},
                {"build", build_flavour()},
                {"simd", simd_level_name(simd_level())}};
  return j;
}

void RunLoop::finish_manifest(const RunSummary& r, double wall,
                              std::chrono::steady_clock::time_point end) {
  io::Manifest& manifest = session_.manifest();
  auto& m = manifest.json();
  m["stop_reason"] = r.stop_reason;
  m["steps"] = r.steps;
  m["time_s"] = r.time;
  m["wall_seconds"] = wall;
  session_.end("finished")["wall_seconds"] =
      std::chrono::duration<double>(end - session_.wall_start()).count();
  if (session_.checkpoints() && !opt_.keep_checkpoints) {
    io::remove_checkpoints(out_);
    m["last_checkpoint"] = nullptr;
  }
  manifest.write_quietly();
}

RunSummary RunLoop::finish() {
  write_final_outputs();
  RunSummary r = partial_summary();
  const auto end = std::chrono::steady_clock::now();
  const double wall =
      wall_before_ + std::chrono::duration<double>(end - session_.wall_start()).count();
  const double loop_s =
      loop_before_ + std::chrono::duration<double>(loop_end_ - loop_start_).count();
  r.json = summary_json(r, wall, loop_s);
  io::write_file_atomically(out_ / "summary.json", r.json.dump(2) + "\n");
  r.history_columns = history_.columns();
  r.history_rows = history_.data();
  finish_manifest(r, wall, end);
  io::run_plot_tool("plot_history.py", out_);  // load_displacement.png, once the run is complete
  if (!Progress::quiet_default()) {
    const Energy& e = r.energy;
    fmt::print(stderr,
               "stopped by {} after {} steps (t = {:.4g} s); peak load {:.6g} N at {:.4g} m; "
               "energy balance: external work {:.6g} J = strain {:.6g} + kinetic {:.4g} + "
               "dissipated {:.6g} J (error {:.3f}%)\n",
               r.stop_reason, r.steps, r.time, r.peak_load, r.displacement_at_peak, e.external_work,
               e.strain, e.kinetic, e.dissipated(), 100.0 * e.balance_error());
  }
  return r;
}

// The run's first files and the session's start, once the set-up has passed every check, so a
// refused run leaves nothing.
void start(const Scenario& sc, const fs::path& out, const RunOptions& opt, RunSession& session,
           const Simulation& sim) {
  if (!opt.resume) {
    io::write_file_atomically(out / "scenario.toml", sc.text);
    io::write_particles_vtu(out / "particles_initial.vtu", sim.specimen(), sc.output.binary_vtu);
  }
  session.started();
  if (opt.on_started) opt.on_started();
  if (!Progress::quiet_default()) print_set_up(sc, sim);
}

// The specimen and its solver, the set-up's failures named after the scenario.
// Distributed, every rank builds at once and the run starts only if all did.
void build(const Scenario& sc, const fs::path& out, const RunOptions& opt, RunSession& session,
           std::optional<Simulation>& sim) {
  if (opt.ranks) opt.ranks->start(sc);
  std::string failure;
  try {
    sim.emplace(sc, build_specimen(sc));
    if (opt.ranks) sim->distribute(opt.ranks->comm(), TestMeasures(*sim, sc).gauge_particles());
  } catch (const Error& e) {
    if (!opt.ranks) rethrow_naming(sc.source.string(), e);
    failure = e.what();
  }
  if (opt.ranks && !opt.ranks->built(failure)) rethrow_naming(sc.source.string(), Error(failure));
  start(sc, out, opt, session, *sim);
}

// The loop over a built simulation, a failure recorded in the manifest once the run has started.
template <class Body>
RunSummary guarded(RunSession& session, Body&& body) {
  try {
    return body();
  } catch (const Error& e) {
    session.record_failure(e.what());
    throw;
  } catch (const std::exception& e) {
    session.record_failure(std::string("internal error: ") + e.what());
    throw;
  }
}

}  // namespace

RunSummary run_scenario(const Scenario& sc, const fs::path& out, const RunOptions& opt,
                        const std::function<void(const Simulation&)>& on_step) {
  validate_run(sc);
  StepThreads threads(opt.threads);
  RunSession session(sc, out, opt);
  return guarded(session, [&] {
    std::optional<Simulation> sim;
    build(sc, out, opt, session, sim);
    RunLoop loop(sc, out, opt, session, *sim, threads);
    return loop.run(on_step) ? loop.finish() : loop.interrupted();
  });
}

RunSummary run_simulation(const Scenario& sc, Simulation& sim, const fs::path& out,
                          const RunOptions& opt) {
  validate_run(sc);
  StepThreads threads(opt.threads);
  RunSession session(sc, out, opt);
  return guarded(session, [&] {
    start(sc, out, opt, session, sim);
    RunLoop loop(sc, out, opt, session, sim, threads);
    return loop.run({}) ? loop.finish() : loop.interrupted();
  });
}

}  // namespace rcdem
