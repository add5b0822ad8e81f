#include "rcdem/study/case_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <vector>

#include "rcdem/core/error.hpp"
#include "rcdem/run/run_manifest.hpp"

namespace rcdem {

namespace fs = std::filesystem;

namespace {

// The fields of summary.json a study's tables read, and the type each must have.
enum class Kind { number, integer, text, object };
struct Field {
  const char* name;
  Kind kind;
};
constexpr Field kSummaryFields[] = {
    {"stop_reason", Kind::text},      {"steps", Kind::integer},
    {"time_s", Kind::number},         {"time_step_s", Kind::number},
    {"peak_load_N", Kind::number},    {"displacement_at_peak_m", Kind::number},
    {"seconds", Kind::number},        {"energy", Kind::object}};

bool has_kind(const nlohmann::json& v, Kind k) {
  switch (k) {
    case Kind::number:
      return v.is_number();
    case Kind::integer:
      return v.is_number_integer();
    case Kind::text:
      return v.is_string();
    case Kind::object:
      return v.is_object();
  }
  return false;
}

const char* kind_name(Kind k) {
  return k == Kind::number    ? "a number"
         : k == Kind::integer ? "an integer"
         : k == Kind::text    ? "a string"
                              : "an object";
}

nlohmann::json parse_file(const fs::path& file, const char* what) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) fail("{}: cannot read the {}", file.string(), what);
  const auto j = nlohmann::json::parse(io::read_text(file), nullptr, false);
  if (j.is_discarded()) fail("{}: not valid JSON (the {} is damaged)", file.string(), what);
  if (!j.is_object()) fail("{}: expected a JSON object (the {} is damaged)", file.string(), what);
  return j;
}

// The step of history.csv's last row, checking that every row has the header's columns (a file
// cut mid-row has one short row).
long long last_history_step(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) fail("{}: missing or unreadable (a finished run writes it)", file.string());
  std::string line;
  if (!std::getline(in, line) || line.rfind("step,", 0) != 0)
    fail("{}: no header line starting with 'step,' (the file is damaged)", file.string());
  const auto columns = std::count(line.begin(), line.end(), ',');
  long long row = 1, last = -1;
  while (std::getline(in, line)) {
    ++row;
    if (std::count(line.begin(), line.end(), ',') != columns)
      fail("{}: line {} has {} fields, the header {} (the file is cut or damaged)", file.string(),
           row, std::count(line.begin(), line.end(), ',') + 1, columns + 1);
    char* end = nullptr;
    last = std::strtoll(line.c_str(), &end, 10);
    if (end == line.c_str() || *end != ',')
      fail("{}: line {} does not start with a step number", file.string(), row);
  }
  if (row == 1) fail("{}: no row after the header (the file is cut)", file.string());
  return last;
}

}  // namespace

nlohmann::json read_run_summary(const fs::path& file) {
  nlohmann::json j = parse_file(file, "run's summary");
  for (const Field& f : kSummaryFields)
    if (!j.contains(f.name) || !has_kind(j[f.name], f.kind))
      fail("{}: '{}' should be {} (the summary is damaged)", file.string(), f.name,
           kind_name(f.kind));
  if (!j["energy"].contains("balance_error") || !j["energy"]["balance_error"].is_number())
    fail("{}: 'energy.balance_error' should be a number (the summary is damaged)", file.string());
  return j;
}

FinishedCase check_finished_case(const fs::path& dir, const Scenario& scenario) {
  FinishedCase c;
  try {
    const nlohmann::json manifest = parse_file(dir / "manifest.json", "run's manifest");
    std::error_code ec;
    const io::Inputs now = io::scenario_inputs(scenario.text, fs::absolute(scenario.source, ec));
    const std::string hash = fmt::format("{:016x}", now.hash);
    if (!manifest.contains("inputs_hash") || !manifest["inputs_hash"].is_string())
      fail("{}: no 'inputs_hash' (the manifest is damaged)", (dir / "manifest.json").string());
    if (manifest["inputs_hash"].get<std::string>() != hash) {
      c.state = FinishedCase::State::scenario_changed;
      c.why = fmt::format(
          "its scenario or an included fragment changed since it ran (inputs hash {} then, {} "
          "now)",
          manifest["inputs_hash"].get<std::string>(), hash);
      return c;
    }
    c.summary = read_run_summary(dir / "summary.json");
    const long long steps = c.summary["steps"].get<long long>();
    const long long last = last_history_step(dir / "history.csv");
    if (last != steps)
      fail("{}: its last row is step {}, but the run ended at step {} (summary.json): the file is "
           "cut",
           (dir / "history.csv").string(), last, steps);
    c.state = FinishedCase::State::finished;
  } catch (const Error& e) {
    c.state = FinishedCase::State::damaged;
    c.why = e.what();
  }
  return c;
}

}  // namespace rcdem
