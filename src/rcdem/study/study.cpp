#include "rcdem/study/study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/io/atomic_file.hpp"
#include "rcdem/io/plot_tool.hpp"
#include "rcdem/io/scenario.hpp"
#include "rcdem/solver/run.hpp"

namespace rcdem {

namespace fs = std::filesystem;

namespace {

const char* const kBuiltinStudies[] = {"three_point_bending"};

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
    case InterfaceLaw::EL: return "EL";
    case InterfaceLaw::NL_A: return "NL-A";
    case InterfaceLaw::NL_B: return "NL-B";
  }
  return "none";
}

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    fail("{}: not a readable summary ({}); delete the case's directory to rerun it",
         file.string(), e.what());
  }
  return j;
}

struct CaseRecord {
  std::string name, model, interface, status;  // status: finished, failed, not run
  nlohmann::json summary;                      // the case's summary.json when finished
  std::string error;
};

void write_tables(const fs::path& out, const std::vector<CaseRecord>& cases,
                  const StudyOptions& o) {
  std::string peaks = "model,interface,peak_load_N,deflection_at_peak_m\n";
  std::string table =
      "case,model,interface,status,stop_reason,steps,time_step_s,wall_time_s,peak_load_N,"
      "deflection_at_peak_m,energy_balance_error\n";
  nlohmann::json study;
  study["study"] = o.label;
  study["scenarios"] = fs::absolute(o.scenarios).lexically_normal().string();
  study["cases"] = nlohmann::json::array();
  for (const auto& c : cases) {
    nlohmann::json jc = {{"case", c.name}, {"status", c.status}};
    if (!c.error.empty()) jc["error"] = c.error;
    if (c.status == "finished") {
      const auto& s = c.summary;
      peaks += fmt::format("{},{},{:.9g},{:.9g}\n", c.model, c.interface,
                           s.value("peak_load_N", 0.0), s.value("displacement_at_peak_m", 0.0));
      table += fmt::format("{},{},{},{},{},{},{:.6g},{:.1f},{:.9g},{:.9g},{:.3g}\n", c.name,
                           c.model, c.interface, c.status, s.value("stop_reason", ""),
                           s.value("steps", 0L), s.value("time_step_s", 0.0),
                           s.value("seconds", 0.0), s.value("peak_load_N", 0.0),
                           s.value("displacement_at_peak_m", 0.0),
                           s["energy"].value("balance_error", 0.0));
      jc["wall_time_s"] = s.value("seconds", 0.0);
    } else {
      table += fmt::format("{},{},{},{},,,,,,,\n", c.name, c.model, c.interface, c.status);
    }
    study["cases"].push_back(jc);
  }
  io::write_file_atomically(out / "peak_loads.csv", peaks);
  io::write_file_atomically(out / "cases.csv", table);
  io::write_file_atomically(out / "study.json", study.dump(2) + "\n");
}

}  // namespace

fs::path builtin_study_scenarios(const std::string& name, bool quick) {
  if (std::find(std::begin(kBuiltinStudies), std::end(kBuiltinStudies), name) ==
      std::end(kBuiltinStudies))
    fail("unknown study '{}': the built-in studies are: three_point_bending (or give a directory "
         "of scenarios with --scenarios)",
         name);
  const fs::path rel = fs::path("examples") / name / "study" / (quick ? "quick" : "");
  for (const fs::path& root : {fs::path("."), fs::path(RCDEM_SOURCE_DIR)})
    if (fs::is_directory(root / rel)) return (root / rel).lexically_normal();
  fail("study '{}': its scenarios ({}) are neither under the working directory nor under the "
       "source tree {}",
       name, rel.string(), RCDEM_SOURCE_DIR);
}

int run_study(const StudyOptions& o) {
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
  // Every scenario is read and checked before anything runs: a typo in the last case should not
  // surface hours into the study.
  std::vector<std::pair<fs::path, Scenario>> todo;
  for (const auto& f : files) {
    if (!wanted.empty() && !wanted.count(f.stem().string())) continue;
    Scenario s = load_scenario(f);
    validate_run(s);
    todo.emplace_back(f, std::move(s));
  }
  std::error_code ec;
  fs::create_directories(o.out / "cases", ec);
  if (ec) fail("{}: cannot create the study's directory: {}", o.out.string(), ec.message());

  const bool quiet = Progress::quiet_default();
  std::vector<CaseRecord> records;
  int failed = 0;
  for (std::size_t i = 0; i < todo.size(); ++i) {
    const auto& [file, sc] = todo[i];
    CaseRecord rec;
    rec.name = file.stem().string();
    rec.model = rec.name.substr(0, rec.name.find('_'));
    rec.interface = interface_name(sc);
    const fs::path dir = o.out / "cases" / rec.name;
    const fs::path summary = dir / "summary.json";
    if (fs::exists(summary) && !o.force) {
      rec.summary = read_json(summary);
      rec.status = "finished";
      if (!quiet)
        fmt::print(stderr, "[{}/{}] {}: finished earlier (peak {:.4g} kN), not rerun\n", i + 1,
                   todo.size(), rec.name, rec.summary.value("peak_load_N", 0.0) / 1e3);
    } else {
      // A directory without summary.json is a run that was interrupted: it starts again.
      if (fs::exists(dir)) fs::remove_all(dir, ec);
      if (ec) fail("{}: cannot clear the interrupted case: {}", dir.string(), ec.message());
      fs::create_directories(dir);
      if (!quiet)
        fmt::print(stderr, "[{}/{}] {}: running ({})\n", i + 1, todo.size(), rec.name,
                   file.string());
      try {
        run_scenario(sc, dir);
        rec.summary = read_json(summary);
        rec.status = "finished";
      } catch (const Error& e) {
        // One case failing (an instability, say) should not cost the others.
        rec.status = "failed";
        rec.error = e.what();
        ++failed;
        fmt::print(stderr, "{}: failed: {}\n", rec.name, e.what());
      }
    }
    records.push_back(rec);
    std::vector<CaseRecord> all = records;
    for (std::size_t k = i + 1; k < todo.size(); ++k)
      all.push_back({todo[k].first.stem().string(),
                     todo[k].first.stem().string().substr(0, todo[k].first.stem().string().find('_')),
                     interface_name(todo[k].second), "not run", {}, {}});
    write_tables(o.out, all, o);  // after every case, so that a stopped study still has its table
  }
  if (!o.report_script.empty()) io::run_plot_tool(o.report_script, o.out);
  if (!quiet)
    fmt::print(stderr, "study {}: {} of {} cases finished; tables and figures in {}\n", o.label,
               todo.size() - static_cast<std::size_t>(failed), todo.size(), o.out.string());
  return failed;
}

}  // namespace rcdem
