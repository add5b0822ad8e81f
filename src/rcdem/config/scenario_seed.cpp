#include "rcdem/config/scenario_seed.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <optional>
#include <sstream>
#include <vector>

#include "rcdem/config/scenario_text.hpp"
#include "rcdem/core/error.hpp"

namespace rcdem::config {

namespace {

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines, bool final_newline) {
  std::string out;
  for (std::size_t i = 0; i < lines.size(); ++i)
    out += lines[i] + (i + 1 < lines.size() || final_newline ? "\n" : "");
  return out;
}

// The line (0-based) and column range [begin, end) (0-based bytes) of a node on one line, if it
// lies on one line whose text before it is ASCII (toml++ counts columns in code points).
bool single_line_span(const toml::node& n, const std::vector<std::string>& lines, std::size_t& line,
                      std::size_t& begin, std::size_t& end) {
  const auto& s = n.source();
  if (s.begin.line == 0 || s.begin.line != s.end.line || s.begin.line > lines.size()) return false;
  line = s.begin.line - 1;
  begin = s.begin.column - 1;
  end = s.end.column - 1;
  const std::string& l = lines[line];
  if (end > l.size() || begin >= end) return false;
  for (std::size_t i = 0; i < end; ++i)
    if (static_cast<unsigned char>(l[i]) >= 0x80) return false;
  return true;
}

}  // namespace

std::string with_generation_seed(const std::string& text, const std::string& source,
                                 std::uint64_t seed) {
  const toml::table table = parse_scenario_toml(text, source);
  std::vector<std::string> lines = split_lines(text);
  const std::string value = fmt::format("{}", seed);
  const toml::node* generation = table.get("generation");
  if (generation && !generation->is_table()) fail("{}: key 'generation': expected a table", source);
  const toml::node* old = generation ? generation->as_table()->get("seed") : nullptr;
  std::size_t line = 0, begin = 0, end = 0;
  if (old) {
    if (!single_line_span(*old, lines, line, begin, end))
      fail("{}:{}: cannot set generation.seed there; set it in the file", source,
           old->source().begin.line);
    lines[line].replace(begin, end - begin, value);
  } else if (generation && single_line_span(*generation, lines, line, begin, end) &&
             lines[line].compare(begin, 12, "[generation]") == 0) {
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(line) + 1, "seed = " + value);
  } else {
    // No [generation] header (absent, or only its sub-tables): a table appended at the end. A
    // generation made of dotted keys or an inline table cannot take it: the check below says so.
    lines.insert(lines.end(), {"", "[generation]", "seed = " + value});
  }
  const std::string out = join_lines(lines, old == nullptr || text.empty() || text.back() == '\n');
  // The edit must give the seed asked for: the text parsed again and checked.
  std::optional<std::int64_t> got;
  try {
    got = toml::parse(out, source)["generation"]["seed"].value<std::int64_t>();
  } catch (const toml::parse_error&) {
  }
  if (!got || static_cast<std::uint64_t>(*got) != seed)
    fail("{}: cannot add generation.seed = {} to this file's generation keys; set it in the file",
         source, seed);
  return out;
}

Scenario load_scenario_on_seed(const std::filesystem::path& path,
                               std::optional<std::uint64_t> seed) {
  if (!seed) return load_scenario(path);
  Scenario s = parse_scenario(
      with_generation_seed(read_scenario_file(path, "scenario"), path.string(), *seed),
      path.string());
  s.source = path;
  return s;
}

}  // namespace rcdem::config
