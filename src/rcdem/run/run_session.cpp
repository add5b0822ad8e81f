#include "rcdem/run/run_session.hpp"

#include <fmt/format.h>

#include "rcdem/core/build_info.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/thread_count_tuner.hpp"
#include "rcdem/run/checkpoint.hpp"

namespace rcdem {

namespace fs = std::filesystem;

RunSession::RunSession(const Scenario& sc, const fs::path& out, const RunOptions& opt)
    : out_(out),
      opt_(opt),
      wall_start_(std::chrono::steady_clock::now()),
      checkpoints_(opt.resume || opt.handle_signals || opt.checkpoint_every_steps > 0 ||
                   opt.checkpoint_every_seconds > 0.0 || static_cast<bool>(opt.decide)),
      lock_(out, checkpoints_ && !opt.lock_held),
      signals_(opt.handle_signals, out / "run.lock", opt.resume),
      manifest_(out, opt.manifest),
      manifest_started_(opt.resume) {
  if (opt.resume) manifest_.load_existing();
  scenario_file_ = scenario_file(sc);
  inputs_ = io::scenario_inputs(sc.text, scenario_file_);
  if (opt.resume) check_inputs_unchanged();
  fill_manifest(sc);
  if (!opt.resume) {
    // --force over an earlier run: its checkpoints must not be resumed into this one.
    io::remove_checkpoints(out);
  } else {
    io::remove_stale_temporaries(out);
  }
}

// Where the scenario lives (its includes are resolved from there): as the manifest says when
// resuming, else the file given.
fs::path RunSession::scenario_file(const Scenario& sc) {
  if (opt_.resume) {
    const auto& j = manifest_.json();
    return j.contains("scenario_file") && j["scenario_file"].is_string()
               ? fs::path(j["scenario_file"].get<std::string>())
               : out_ / "scenario.toml";
  }
  std::error_code ec;
  return sc.source.empty() ? fs::path() : fs::absolute(sc.source, ec);
}

// Which input changed, if one did (the checkpoint would only say that something did).
void RunSession::check_inputs_unchanged() {
  const auto& j = manifest_.json();
  if (!j.contains("inputs") || !j["inputs"].is_array()) return;
  bool first = true;
  for (const auto& was : j["inputs"]) {
    const std::string path = was.value("path", ""), hash = was.value("fnv1a64", "");
    // The first input is the scenario's text, which a resume reads from the run's own copy.
    const std::string named = first ? (out_ / "scenario.toml").string() : path;
    first = false;
    bool found = false;
    for (const auto& now : inputs_.list)
      if (now["path"] == path) {
        found = true;
        if (now["fnv1a64"] != hash)
          fail(
              "cannot resume '{}': the scenario input '{}' changed since the run started "
              "(FNV-1a {} then, {} now); restore it, or start a new run",
              out_.string(), named, hash, now["fnv1a64"].get<std::string>());
      }
    if (!found)
      fail("cannot resume '{}': the scenario no longer reads '{}' as it did when the run started",
           out_.string(), path);
  }
}

void RunSession::fill_manifest(const Scenario& sc) {
  auto& j = manifest_.json();
  const std::string version = build_version(), git = build_git_hash();
  if (!opt_.resume) {
    j["manifest_version"] = 1;
    j["scenario"] = sc.source.string();
    j["scenario_file"] = scenario_file_.string();
    j["scenario_copy"] = "scenario.toml";
    j["inputs"] = inputs_.list;
    j["inputs_hash"] = fmt::format("{:016x}", inputs_.hash);
    j["seed"] = sc.generation.seed;
    j["set"] = sc.overrides;  // --set KEY=VALUE items, already in scenario.toml's text
    j["command"] = opt_.command;
    j["rcdem_version"] = version;
    j["git_hash"] = git;
    j["build"] = build_flavour();
    j["threads"] = runtime_thread_count();
    j["start_time"] = io::iso_now();
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
  j["threads"] = runtime_thread_count();
  j["exit_state"] = "running";
  j["end_time"] = nullptr;
  j["sessions"].push_back({{"start_time", io::iso_now()},
                           {"end_time", nullptr},
                           {"rcdem_version", version},
                           {"git_hash", git},
                           {"build", build_flavour()},
                           {"threads", runtime_thread_count()},
                           {"command", opt_.command},
                           {"resumed_from", nullptr},
                           {"exit_state", "running"}});
  if (!opt_.checkpoint_every_text.empty()) {
    j["checkpoint_every"] = opt_.checkpoint_every_text;
    j["sessions"].back()["checkpoint_every"] = opt_.checkpoint_every_text;
  }
}

void RunSession::started() {
  manifest_.write();
  manifest_started_ = true;
}

nlohmann::ordered_json& RunSession::end(const std::string& state) {
  auto& j = manifest_.json();
  j["exit_state"] = state;
  j["end_time"] = io::iso_now();
  auto& session = manifest_.session();
  session["exit_state"] = state;
  session["end_time"] = j["end_time"];
  return session;
}

void RunSession::record_failure(const std::string& what) {
  if (!manifest_started_) return;
  manifest_.json()["error"] = what;
  end("failed")["error"] = what;
  manifest_.write_quietly();
}

}  // namespace rcdem
