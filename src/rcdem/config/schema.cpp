#include "rcdem/config/schema.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace rcdem::config {

Schema& Schema::section(std::string path, std::string doc) {
  sections_.push_back({std::move(path), std::move(doc)});
  return *this;
}

Schema& Schema::key(KeyDecl decl) {
  keys_.push_back(std::move(decl));
  return *this;
}

bool path_matches(const std::string& pattern, const std::string& path) {
  // A '*' segment in a declared path stands for any one name ("plates.*.face").
  std::size_t i = 0, j = 0;
  while (i < pattern.size() && j < path.size()) {
    if (pattern[i] == '*') {
      ++i;
      while (j < path.size() && path[j] != '.') ++j;
      continue;
    }
    if (pattern[i] != path[j]) return false;
    ++i;
    ++j;
  }
  return i == pattern.size() && j == path.size();
}

const KeyDecl* Schema::find_key(const std::string& path) const {
  for (const auto& k : keys_)
    if (path_matches(k.path, path)) return &k;
  return nullptr;
}

bool Schema::is_section(const std::string& path) const {
  return std::any_of(sections_.begin(), sections_.end(),
                     [&](const SectionDecl& s) { return path_matches(s.path, path); });
}

std::vector<std::string> Schema::keys_in_section(const std::string& section) const {
  std::vector<std::string> names;
  const auto child = [&](const std::string& path) -> std::optional<std::string> {
    const auto dot = path.rfind('.');
    const std::string parent = dot == std::string::npos ? "" : path.substr(0, dot);
    if (!(parent == section || path_matches(parent, section))) return std::nullopt;
    return path.substr(dot == std::string::npos ? 0 : dot + 1);
  };
  for (const auto& k : keys_)
    if (auto n = child(k.path)) names.push_back(*n);
  for (const auto& s : sections_)
    if (auto n = child(s.path); n && s.path != section) names.push_back("[" + s.path + "]");
  return names;
}

std::string format_value(const Value& value) {
  struct Visitor {
    std::string operator()(double v) const {
      std::string s = fmt::format("{}", v);
      if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
      return s;
    }
    std::string operator()(std::int64_t v) const { return fmt::format("{}", v); }
    std::string operator()(bool v) const { return v ? "true" : "false"; }
    std::string operator()(const std::string& v) const { return fmt::format("\"{}\"", v); }
    std::string operator()(const std::vector<double>& v) const {
      std::string s = "[";
      for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + (*this)(v[i]);
      return s + "]";
    }
    std::string operator()(const std::vector<std::string>& v) const {
      std::string s = "[";
      for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + (*this)(v[i]);
      return s + "]";
    }
  };
  return std::visit(Visitor{}, value);
}

namespace {

std::string describe_range(const Range& r) {
  const bool has_min = std::isfinite(r.min);
  const bool has_max = std::isfinite(r.max);
  if (has_min && has_max)
    return fmt::format("in {}{:g}, {:g}{}", r.min_exclusive ? "(" : "[", r.min, r.max,
                       r.max_exclusive ? ")" : "]");
  if (has_min) return fmt::format("{} {:g}", r.min_exclusive ? ">" : ">=", r.min);
  if (has_max) return fmt::format("{} {:g}", r.max_exclusive ? "<" : "<=", r.max);
  return "";
}

}  // namespace

std::string Schema::describe_expected(const KeyDecl& decl) {
  std::string what;
  switch (decl.type) {
    case KeyType::Real:
      what = "a number";
      break;
    case KeyType::Integer:
      what = "an integer";
      break;
    case KeyType::Boolean:
      what = "true or false";
      break;
    case KeyType::String: {
      if (decl.choices.empty()) return "a string";
      what = "one of";
      for (std::size_t i = 0; i < decl.choices.size(); ++i)
        what += fmt::format("{}\"{}\"", i ? ", " : " ", decl.choices[i]);
      return what;
    }
    case KeyType::RealArray:
      what = decl.array_step > 0
                 ? fmt::format("an array of {} n numbers (n >= 2 points)", decl.array_step)
                 : fmt::format("an array of {} numbers", decl.array_size);
      break;
    case KeyType::StringArray:
      return "an array of names";
  }
  const std::string range = describe_range(decl.range);
  if (!range.empty()) what += (decl.type == KeyType::RealArray ? ", each " : " ") + range;
  if (!decl.unit.empty()) what += fmt::format(" (unit: {})", decl.unit);
  return what;
}

void Schema::print_template(std::ostream& out) const {
  out << "# rcdem scenario template: every key with its default, unit and admissible range.\n"
         "# SI units throughout (m, kg, s, N, Pa, J/m^2). Keys marked 'required' have no "
         "default.\n";
  std::vector<std::string> printed_sections;
  for (const auto& s : sections_) {
    // A named section ("plates.*") is shown commented out, as an example with the name "NAME":
    // the template stays a valid scenario.
    const bool named = s.path.find('*') != std::string::npos;
    const std::string lead = named ? "# " : "";
    std::string header = s.path;
    for (auto star = header.find('*'); star != std::string::npos; star = header.find('*'))
      header.replace(star, 1, "NAME");
    out << "\n# " << s.doc << "\n" << lead << "[" << header << "]";
    if (named) out << "   # one such section per item; NAME is yours to choose";
    out << "\n";
    for (const auto& k : keys_) {
      const auto dot = k.path.rfind('.');
      if (k.path.substr(0, dot) != s.path) continue;
      const std::string name = k.path.substr(dot + 1);
      out << "# " << k.doc << "\n# expected: " << describe_expected(k) << "\n";
      if (k.default_value)
        out << lead << name << " = " << format_value(*k.default_value) << "\n";
      else
        out << "# " << name << " = ...   # required\n";
    }
  }
}

}  // namespace rcdem::config
