#pragma once
// A study: a directory of scenarios run one after another into one output directory, resumable
// (a case with a summary.json is finished and is not rerun), then summarised by a report script.
// The paper's three-point bending study (SPEC 10, Table 3) is the built-in one.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rcdem {

struct StudyOptions {
  std::filesystem::path scenarios;  // directory of *.toml, one per case
  std::filesystem::path out;        // DIR: DIR/cases/<case>/ per case, tables and figures in DIR
  std::vector<std::string> cases;   // run only these (scenario stems); empty: all
  // Run every case on each of these packings (generation.seed), into DIR/cases/<case>_seed<N>/;
  // empty: each case on its scenario's own seed, into DIR/cases/<case>/.
  std::vector<std::uint64_t> seeds;
  std::vector<std::string> sets;  // --set KEY=VALUE items applied to every case
  // --sweep KEY=V1,V2,...: every case once per value, into DIR/cases/<case>_<LEAF>=<V>[_seed<N>]/
  // (LEAF: the key's last part); empty: no sweep.
  std::string sweep;
  std::string report_script;  // tools/<script> run on DIR at the end ("" for none)
  std::string label;          // what the study is, for study.json and messages
  bool force = false;         // rerun finished cases
  int jobs = 1;               // cases run side by side (each a child `rcdem run`)
  int threads_per_job = 1;    // OpenMP threads of each child
};

// Where a built-in study's scenarios live: examples/<name>/study (quick: .../study/quick), among
// rcdem's own files (installed beside it, or the source tree it was built from; never the working
// directory). Fails with the list of known studies if `name` is none of them.
std::filesystem::path builtin_study_scenarios(const std::string& name, bool quick);

// Runs the study; returns the number of cases that failed (0: all finished), or -1 when a signal
// interrupted it (each running case checkpointed; the same call resumes).
int run_study(const StudyOptions& options);

}  // namespace rcdem
