#include "rcdem/study/study.hpp"

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "rcdem/config/scenario.hpp"
#include "rcdem/config/scenario_overrides.hpp"
#include "rcdem/core/child_process.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/core/stop_signals.hpp"
#include "rcdem/io/atomic_file.hpp"
#include "rcdem/io/plot_tool.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/run/run.hpp"
#include "rcdem/run/run_manifest.hpp"
#include "rcdem/study/case_check.hpp"

namespace rcdem {

namespace fs = std::filesystem;

namespace {

const char* const kBuiltinStudies[] = {"three_point_bending", "size_series"};

volatile std::sig_atomic_t g_study_signal = 0;
extern "C" void on_study_signal(int sig) { g_study_signal = sig; }

std::vector<fs::path> list_scenarios(const fs::path& dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file() && it->path().extension() == ".toml") files.push_back(it->path());
  if (ec) fail("{}: cannot read the study's scenario directory: {}", dir.string(), ec.message());
  std::sort(files.begin(), files.end());
  if (files.empty()) fail("{}: no scenario (*.toml) in the study's directory", dir.string());
  return files;
}

// Model and interface of a case, for the tables: the model is the name up to its first '_'
// (AN2_NL-B -> AN2), the interface that of its bars ("none" without bars).
std::string interface_name(const Scenario& s) {
  if (s.bars.empty()) return "none";
  switch (s.bars.front().interface) {
    case InterfaceLaw::EL:
      return "EL";
    case InterfaceLaw::NL_A:
      return "NL-A";
    case InterfaceLaw::NL_B:
      return "NL-B";
  }
  return "none";
}

struct CaseRecord {
  std::string name, model, interface, status;  // status: finished, failed, not run
  std::string variant;                         // a sweep's KEY=VALUE, or ""
  std::uint64_t seed = 0;                      // the packing it runs on
  std::string dir;                             // its run directory under DIR/cases
  nlohmann::json summary;                      // the case's summary.json when finished
  std::string error;
  std::string label() const {
    if (dir == name) return name;
    return variant.empty() ? fmt::format("{} (seed {})", name, seed)
                           : fmt::format("{} ({}, seed {})", name, variant, seed);
  }
};

void write_tables(const fs::path& out, const std::vector<CaseRecord>& cases,
                  const StudyOptions& o) {
  std::string peaks =
      "case,directory,variant,model,interface,seed,peak_load_N,deflection_at_peak_m\n";
  std::string table =
      "case,seed,directory,variant,model,interface,status,stop_reason,steps,time_step_s,"
      "wall_time_s,peak_load_N,deflection_at_peak_m,energy_balance_error\n";
  nlohmann::json study;
  study["study"] = o.label;
  study["scenarios"] = fs::absolute(o.scenarios).lexically_normal().string();
  study["seeds"] = o.seeds;
  study["sweep"] = o.sweep;
  study["cases"] = nlohmann::json::array();
  for (const auto& c : cases) {
    nlohmann::json jc = {{"case", c.name},
                         {"seed", c.seed},
                         {"directory", c.dir},
                         {"variant", c.variant},
                         {"status", c.status}};
    if (!c.error.empty()) jc["error"] = c.error;
    if (c.status == "finished") {
      const auto& s = c.summary;
      peaks += fmt::format("{},{},{},{},{},{},{:.9g},{:.9g}\n", c.name, c.dir, c.variant, c.model,
                           c.interface, c.seed, s.value("peak_load_N", 0.0),
                           s.value("displacement_at_peak_m", 0.0));
      table += fmt::format("{},{},{},{},{},{},{},{},{},{:.6g},{:.1f},{:.9g},{:.9g},{:.3g}\n",
                           c.name, c.seed, c.dir, c.variant, c.model, c.interface, c.status,
                           s.value("stop_reason", ""), s.value("steps", 0L),
                           s.value("time_step_s", 0.0), s.value("seconds", 0.0),
                           s.value("peak_load_N", 0.0), s.value("displacement_at_peak_m", 0.0),
                           s["energy"].value("balance_error", 0.0));
      jc["wall_time_s"] = s.value("seconds", 0.0);
    } else {
      table += fmt::format("{},{},{},{},{},{},{},,,,,,,\n", c.name, c.seed, c.dir, c.variant,
                           c.model, c.interface, c.status);
    }
    study["cases"].push_back(jc);
  }
  io::write_file_atomically(out / "peak_loads.csv", peaks);
  io::write_file_atomically(out / "cases.csv", table);
  io::write_file_atomically(out / "study.json", study.dump(2) + "\n");
}

// `rcdem run SCENARIO -o DIR --force [--seed N]` (or `rcdem run --resume DIR`) as a child
// process, output to DIR/run.log (appended to on a resume). The child stops (checkpointing) when
// the study dies, even by SIGKILL.
pid_t spawn_run(const fs::path& scenario, const fs::path& dir, int threads, bool resume,
                std::optional<std::uint64_t> seed, const std::vector<std::string>& sets) {
  std::vector<std::string> args =
      resume ? std::vector<std::string>{"rcdem", "run", "--resume", dir.string()}
             : std::vector<std::string>{"rcdem", "run",        scenario.string(),
                                        "-o",    dir.string(), "--force"};
  if (!resume && seed) args.insert(args.end(), {"--seed", std::to_string(*seed)});
  if (!resume)
    for (const auto& item : sets) args.insert(args.end(), {"--set", item});
  SpawnOptions o;
  o.log = dir / "run.log";
  o.append_log = resume;
  o.env_set = {fmt::format("OMP_NUM_THREADS={}", threads)};
  o.stop_with_parent = true;
  // Through /proc/self/exe, not its target: the binary may be rebuilt while a study runs, and
  // the link still reaches the one that is running.
  try {
    return spawn_child("/proc/self/exe", args, o);
  } catch (const Error& e) {
    fail("cannot start a run for {}: {}", scenario.string(), e.what());
  }
}

}  // namespace

fs::path builtin_study_scenarios(const std::string& name, bool quick) {
  if (std::find(std::begin(kBuiltinStudies), std::end(kBuiltinStudies), name) ==
      std::end(kBuiltinStudies))
    fail(
        "unknown study '{}': the built-in studies are: three_point_bending, size_series (or give "
        "a directory of scenarios with --scenarios)",
        name);
  const fs::path rel = fs::path("examples") / name / "study" / (quick ? "quick" : "");
  const fs::path found = own_file(rel);
  std::error_code ec;
  if (found.empty() || !fs::is_directory(found, ec))
    fail(
        "study '{}': its scenarios ({}) are neither installed beside rcdem (share/rcdem) nor in "
        "the source tree {}",
        name, rel.string(), RCDEM_SOURCE_DIR);
  return found;
}

namespace {

// One run of a study: a case's scenario on one packing.
struct StudyCase {
  fs::path file;
  Scenario scenario;
  std::optional<std::uint64_t> seed;  // --seeds' value, or none: the scenario's own
  std::string variant;                // --sweep's KEY=VALUE, or ""
  std::vector<std::string> sets;      // --set's items, and the variant
};

// --sweep KEY=V1,V2,...: its items KEY=V1, KEY=V2, ... ({""} without a sweep), each checked as a
// --set item; the key may not also be given to --set.
std::vector<std::string> sweep_items(const StudyOptions& o) {
  if (o.sweep.empty()) return {""};
  const auto eq = o.sweep.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == o.sweep.size())
    fail("--sweep '{}': expected KEY=V1,V2,... (e.g. contact.sigma_nt=3e6,4.23e6,5.5e6)", o.sweep);
  const std::string key = o.sweep.substr(0, eq);
  std::vector<std::string> items;
  std::set<std::string> distinct;
  std::stringstream values(o.sweep.substr(eq + 1));
  for (std::string v; std::getline(values, v, ',');) {
    if (v.empty() || !distinct.insert(v).second)
      fail("--sweep '{}': expected distinct, non-empty values", o.sweep);
    items.push_back(key + "=" + v);
  }
  for (const auto& item : o.sets)
    if (item.substr(0, item.find('=')) == key)
      fail("--sweep '{}': key '{}' is also given to --set", o.sweep, key);
  for (const auto& item : items)
    for (const config::Override& ov : config::parse_overrides({item})) config::check_override(ov);
  return items;
}

// The runs of a study that --cases and --seeds select, each read and checked before anything
// runs: a typo in the last case should not surface hours into the study.
std::vector<StudyCase> load_cases(const StudyOptions& o) {
  const std::vector<fs::path> files = list_scenarios(o.scenarios);
  std::set<std::string> wanted(o.cases.begin(), o.cases.end());
  for (const auto& w : wanted) {
    if (std::none_of(files.begin(), files.end(),
                     [&](const fs::path& f) { return f.stem() == w; })) {
      std::string known;
      for (const auto& f : files) known += (known.empty() ? "" : ", ") + f.stem().string();
      fail("--cases: no case '{}' in {} (the cases are: {})", w, o.scenarios.string(), known);
    }
  }
  std::set<std::uint64_t> distinct;
  for (const auto seed : o.seeds)
    if (!distinct.insert(seed).second) fail("--seeds: seed {} is given twice", seed);
  std::vector<std::optional<std::uint64_t>> seeds(o.seeds.begin(), o.seeds.end());
  if (seeds.empty()) seeds.push_back(std::nullopt);
  const std::vector<std::string> variants = sweep_items(o);
  std::vector<StudyCase> todo;
  for (const auto& f : files) {
    if (!wanted.empty() && !wanted.count(f.stem().string())) continue;
    for (const auto& variant : variants)
      for (const auto& seed : seeds) {
        std::vector<std::string> sets = o.sets;
        if (!variant.empty()) sets.push_back(variant);
        Scenario s = config::load_scenario_on_seed(f, seed, sets);
        validate_run(s);
        todo.push_back({f, std::move(s), seed, variant, std::move(sets)});
      }
  }
  return todo;
}

// One study's cases as they run: each a child `rcdem run`, with its share of the threads. The
// child checkpoints (every 10 minutes and on a stop signal), so an interrupted case resumes
// where it stopped, and small specimens scale better across processes than across threads.
class StudyRun {
 public:
  StudyRun(const StudyOptions& o, std::vector<StudyCase> todo)
      : o_(o), todo_(std::move(todo)), quiet_(Progress::quiet_default()) {
    for (std::size_t i = 0; i < todo_.size(); ++i) records_.push_back(initial_record(i));
    write_tables(o_.out, records_, o_);
  }

  // Runs the pending cases, o.jobs at a time; false when a signal interrupted the study.
  bool run_pending();
  int failed() const { return failed_; }

 private:
  CaseRecord initial_record(std::size_t i);
  fs::path prepare(std::size_t i);
  void finish(std::size_t i, const std::string& error);
  void start_next(std::map<pid_t, std::size_t>& running, std::size_t& next);

  const StudyOptions& o_;
  std::vector<StudyCase> todo_;
  bool quiet_;
  std::vector<CaseRecord> records_;
  std::vector<std::size_t> pending_;
  std::size_t done_ = 0;
  int failed_ = 0;
};

// A case with a summary.json is finished (unless --force), once checked: a case whose scenario
// changed since it ran is run again; one whose outputs are damaged stops the study, naming the
// file (its results are the user's to keep or delete). Any other case is pending.
CaseRecord StudyRun::initial_record(std::size_t i) {
  const StudyCase& sc = todo_[i];
  CaseRecord rec;
  rec.name = sc.file.stem().string();
  rec.model = rec.name.substr(0, rec.name.find('_'));
  rec.interface = interface_name(sc.scenario);
  rec.seed = sc.scenario.generation.seed;
  rec.variant = sc.variant;
  rec.dir = rec.name;
  if (!sc.variant.empty()) {
    // The key's last part and the value: "AN0_sigma_nt=3e6".
    const std::string key = sc.variant.substr(0, sc.variant.find('='));
    rec.dir += "_" + key.substr(key.rfind('.') + 1) + sc.variant.substr(sc.variant.find('='));
  }
  if (sc.seed) rec.dir += fmt::format("_seed{}", *sc.seed);
  rec.status = "not run";
  const fs::path dir = o_.out / "cases" / rec.dir;
  if (!fs::exists(dir / "summary.json") || o_.force) {
    pending_.push_back(i);
    return rec;
  }
  const FinishedCase found = check_finished_case(dir, sc.scenario);
  if (found.state == FinishedCase::State::damaged)
    fail("{}: a finished case that cannot be trusted: {}; delete {} to run it again", rec.label(),
         found.why, dir.string());
  if (found.state == FinishedCase::State::scenario_changed) {
    pending_.push_back(i);
    if (!quiet_) fmt::print(stderr, "{}: {}; run again\n", rec.label(), found.why);
    return rec;
  }
  rec.summary = found.summary;
  rec.status = "finished";
  if (!quiet_)
    fmt::print(stderr, "{}: finished earlier (peak {:.4g} kN), not rerun\n", rec.label(),
               rec.summary["peak_load_N"].get<double>() / 1e3);
  return rec;
}

// A case directory without summary.json nor a checkpoint (interrupted during its set-up):
// cleared, and the case starts again.
fs::path StudyRun::prepare(std::size_t i) {
  const fs::path dir = o_.out / "cases" / records_[i].dir;
  std::error_code e;
  if (fs::exists(dir)) {
    { const io::RunLock idle(dir, true); }  // refused while a run started by hand is live in it
    fs::remove_all(dir, e);
  }
  if (e) fail("{}: cannot clear the interrupted case: {}", dir.string(), e.message());
  fs::create_directories(dir);
  return dir;
}

void StudyRun::finish(std::size_t i, const std::string& error) {
  CaseRecord& rec = records_[i];
  ++done_;
  std::string why = error;
  if (why.empty()) {
    try {
      rec.summary = read_run_summary(o_.out / "cases" / rec.dir / "summary.json");
    } catch (const Error& e) {
      why = e.what();
    }
  }
  if (why.empty()) {
    rec.status = "finished";
    if (!quiet_)
      fmt::print(stderr, "[{}/{}] {}: finished, peak {:.4g} kN, {:.0f} s\n", done_, pending_.size(),
                 rec.label(), rec.summary["peak_load_N"].get<double>() / 1e3,
                 rec.summary["seconds"].get<double>());
  } else {
    // One case failing (an instability, say) should not cost the others.
    rec.status = "failed";
    rec.error = why;
    ++failed_;
    fmt::print(stderr, "[{}/{}] {}: failed: {}\n", done_, pending_.size(), rec.label(), why);
  }
  write_tables(o_.out, records_, o_);  // after every case, so a stopped study keeps its table
}

// Starts pending cases until o.jobs run.
void StudyRun::start_next(std::map<pid_t, std::size_t>& running, std::size_t& next) {
  while (next < pending_.size() && static_cast<int>(running.size()) < o_.jobs) {
    const std::size_t i = pending_[next++];
    const fs::path existing = o_.out / "cases" / records_[i].dir;
    // A pending case with a summary.json (its scenario changed, or --force) starts afresh.
    const bool resume = !o_.force && !fs::exists(existing / "summary.json") &&
                        fs::exists(existing / "scenario.toml") &&
                        !io::list_checkpoints(existing).empty();
    try {
      const fs::path dir = resume ? existing : prepare(i);
      if (!quiet_)
        fmt::print(stderr, "{}: {} ({}; log {})\n", records_[i].label(),
                   resume ? "resumed from its last checkpoint" : "started", todo_[i].file.string(),
                   (dir / "run.log").string());
      running[spawn_run(todo_[i].file, dir, o_.threads_per_job, resume, todo_[i].seed,
                        todo_[i].sets)] = i;
    } catch (const Error& e) {
      finish(i, e.what());
    }
  }
}

bool StudyRun::run_pending() {
  g_study_signal = 0;
  StopActions old;
  install_stop_handler(on_study_signal, 0, &old);  // no SA_RESTART: waitpid returns EINTR
  std::map<pid_t, std::size_t> running;
  std::size_t next = 0;
  while (next < pending_.size() || !running.empty()) {
    start_next(running, next);
    if (running.empty()) continue;
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0 && errno == EINTR) {
      // A stop signal: passed on (a terminal's ^C reached them already); each run then
      // checkpoints and exits, and no further case starts.
      const int sig = g_study_signal;
      for (const auto& [child, _] : running) ::kill(child, sig);
      next = pending_.size();
      continue;
    }
    if (pid < 0) fail("waiting for the study's runs: {}", std::strerror(errno));
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const std::size_t i = it->second;
    running.erase(it);
    const fs::path dir = o_.out / "cases" / records_[i].dir;
    const bool ok = child_status(status).ok() && fs::exists(dir / "summary.json");
    if (!ok && g_study_signal != 0) {
      ++done_;
      records_[i].status = "interrupted";
      write_tables(o_.out, records_, o_);
      continue;
    }
    finish(i, ok ? "" : last_log_line(dir / "run.log"));
  }
  restore_stop_handlers(old);
  return g_study_signal == 0;
}

// The previous report's files (tools/study_report.py's or size_series_report.py's outputs),
// before a new report is made.
void remove_report(const fs::path& out) {
  std::error_code ec;
  fs::remove_all(out / "curves", ec);
  std::vector<fs::path> old;
  for (fs::directory_iterator it(out, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const bool png = it->path().extension() == ".png";
    // tools/study_report.py's, then tools/size_series_report.py's.
    const bool figure =
        png && (name.rfind("figure", 0) == 0 || name == "crack_height.png" ||
                name == "load_displacement.png" || name.rfind("load_deflection_h", 0) == 0 ||
                name == "sigma_n_vs_h.png" || name == "rho_min_vs_h.png");
    if (figure || name == "table3.md" || name == "report.json" || name == "report.log" ||
        name == "cases.md" || name == "size_series.md" || name == "size_effect.json")
      old.push_back(it->path());
  }
  for (const auto& p : old) fs::remove(p, ec);
}

}  // namespace

int run_study(const StudyOptions& o) {
  std::vector<StudyCase> todo = load_cases(o);
  const std::size_t cases = todo.size();
  std::error_code ec;
  fs::create_directories(o.out / "cases", ec);
  if (ec) fail("{}: cannot create the study's directory: {}", o.out.string(), ec.message());
  // One study at a time in a directory: a second one would clear the first's cases as it sets up.
  const io::RunLock study_lock(o.out, true);
  // The report describes a completed study: whatever stops this one (a damaged case, a signal,
  // the report itself failing) must not leave the previous report looking current.
  if (!o.report_script.empty()) remove_report(o.out);
  StudyRun study(o, std::move(todo));
  if (!study.run_pending()) {
    fmt::print(stderr,
               "study interrupted: every running case wrote a checkpoint; run the same command "
               "again to resume (finished cases are kept)\n");
    return -1;
  }
  if (!o.report_script.empty()) io::run_report_tool(o.report_script, o.out);
  if (!Progress::quiet_default())
    fmt::print(stderr, "study {}: {} of {} cases finished; tables and figures in {}\n", o.label,
               cases - static_cast<std::size_t>(study.failed()), cases, o.out.string());
  return study.failed();
}

}  // namespace rcdem
