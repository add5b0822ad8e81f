#include "rcdem/config/scenario_overrides.hpp"

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


// The line (0-based) of a section's [header], if the file has one written as such.
std::optional<std::size_t> header_line(const toml::table& table, const std::string& section,
                                       const std::vector<std::string>& lines) {
  const toml::node* node = table.at_path(section).node();
  std::size_t line = 0, begin = 0, end = 0;
  if (node && node->is_table() && single_line_span(*node, lines, line, begin, end) &&
      lines[line].compare(begin, section.size() + 2, "[" + section + "]") == 0)
    return line;
  return std::nullopt;
}

std::string formatted(const toml::node& node) {
  std::ostringstream s;
  node.visit([&](const auto& n) { s << toml::toml_formatter(n); });
  return s.str();
}

}  // namespace

std::vector<Override> parse_overrides(const std::vector<std::string>& items) {
  std::vector<Override> out;
  for (const auto& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      fail("--set '{}': expected KEY=VALUE (e.g. solver.damping=0.3)", item);
    Override o{item.substr(0, eq), item.substr(eq + 1), item};
    for (const auto& earlier : out)
      if (earlier.key == o.key) fail("--set: {} is given twice", o.key);
    try {
      (void)toml::parse("v = " + o.value);
    } catch (const toml::parse_error&) {
      // A bare word: the string it spells.
      if (o.value.empty() || o.value.find_first_of("\"'\n\r") != std::string::npos)
        fail("--set '{}': the value is neither a TOML value (0.3, \"text\", [1, 2], true) nor a "
             "bare word",
             item);
      o.value = "\"" + o.value + "\"";
    }
    out.push_back(std::move(o));
  }
  return out;
}

std::string with_override(const std::string& text, const std::string& source, const Override& o) {
  const toml::table table = parse_scenario_toml(text, source);
  std::vector<std::string> lines = split_lines(text);
  const auto dot = o.key.rfind('.');
  const std::string section = dot == std::string::npos ? "" : o.key.substr(0, dot);
  const std::string leaf = dot == std::string::npos ? o.key : o.key.substr(dot + 1);
  const toml::node* old = table.at_path(o.key).node();
  std::size_t line = 0, begin = 0, end = 0;
  if (old && !old->is_table()) {
    if (!single_line_span(*old, lines, line, begin, end))
      fail("{}:{}: cannot set {} there; set it in the file", source, old->source().begin.line,
           o.key);
    lines[line].replace(begin, end - begin, o.value);
  } else if (section.empty()) {
    // Before the first table header: where a top-level key belongs.
    std::size_t at = 0;
    for (; at < lines.size(); ++at) {
      const auto first = lines[at].find_first_not_of(" \t");
      if (first != std::string::npos && lines[at][first] == '[') break;
    }
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(at), leaf + " = " + o.value);
  } else if (const auto header = header_line(table, section, lines)) {
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(*header) + 1, leaf + " = " + o.value);
  } else {
    // No [section] header (absent, or only its sub-tables): a table appended at the end. A
    // section made of dotted keys or an inline table cannot take it: the check below says so.
    lines.insert(lines.end(), {"", "[" + section + "]", leaf + " = " + o.value});
  }
  const std::string out = join_lines(lines, old == nullptr || text.empty() || text.back() == '\n');
  // The edit must give the value asked for: the text parsed again and checked.
  bool same = false;
  try {
    const toml::table now = toml::parse(out, source);
    const toml::table want = toml::parse("v = " + o.value);
    const toml::node* got = now.at_path(o.key).node();
    same = got && formatted(*got) == formatted(*want.get("v"));
  } catch (const toml::parse_error&) {
  }
  if (!same)
    fail("{}: cannot add {} = {} to this file's {} keys; set it in the file", source, o.key,
         o.value, section.empty() ? "top-level" : section);
  return out;
}

std::string with_generation_seed(const std::string& text, const std::string& source,
                                 std::uint64_t seed) {
  const std::string value = fmt::format("{}", seed);
  return with_override(text, source, {"generation.seed", value, "generation.seed=" + value});
}

Scenario load_scenario_on_seed(const std::filesystem::path& path,
                               std::optional<std::uint64_t> seed,
                               const std::vector<std::string>& overrides) {
  const std::vector<Override> set = parse_overrides(overrides);
  for (const auto& o : set)
    if (seed && o.key == "generation.seed")
      fail("give --seed or --set generation.seed, not both");
  std::string text = read_scenario_file(path, "scenario");
  if (seed) text = with_generation_seed(text, path.string(), *seed);
  for (const auto& o : set) {
    check_override(o);
    text = with_override(text, path.string(), o);
  }
  Scenario s = parse_scenario(text, path.string(), set);
  s.source = path;
  return s;
}

}  // namespace rcdem::config
