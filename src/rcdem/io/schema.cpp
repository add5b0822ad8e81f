#include "rcdem/io/schema.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace rcdem::io {

Schema& Schema::section(std::string path, std::string doc) {
  sections_.push_back({std::move(path), std::move(doc)});
  return *this;
}

Schema& Schema::key(KeyDecl decl) {
  keys_.push_back(std::move(decl));
  return *this;
}

const KeyDecl* Schema::find_key(const std::string& path) const {
  for (const auto& k : keys_)
    if (k.path == path) return &k;
  return nullptr;
}

bool Schema::is_section(const std::string& path) const {
  return std::any_of(sections_.begin(), sections_.end(),
                     [&](const SectionDecl& s) { return s.path == path; });
}

std::vector<std::string> Schema::keys_in_section(const std::string& section) const {
  std::vector<std::string> names;
  const std::string prefix = section.empty() ? "" : section + ".";
  for (const auto& k : keys_) {
    if (k.path.rfind(prefix, 0) != 0) continue;
    const std::string rest = k.path.substr(prefix.size());
    if (rest.find('.') == std::string::npos) names.push_back(rest);
  }
  for (const auto& s : sections_) {
    if (s.path.rfind(prefix, 0) != 0 || s.path == section) continue;
    const std::string rest = s.path.substr(prefix.size());
    if (rest.find('.') == std::string::npos) names.push_back("[" + s.path + "]");
  }
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
  };
  return std::visit(Visitor{}, value);
}

namespace {

std::string describe_range(const Range& r) {
  const bool has_min = std::isfinite(r.min);
  const bool has_max = std::isfinite(r.max);
  if (has_min && has_max)
    return fmt::format("in {}{}, {}{}", r.min_exclusive ? "(" : "[", r.min, r.max,
                       r.max_exclusive ? ")" : "]");
  if (has_min) return fmt::format("{} {}", r.min_exclusive ? ">" : ">=", r.min);
  if (has_max) return fmt::format("{} {}", r.max_exclusive ? "<" : "<=", r.max);
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
      what = "one of";
      for (std::size_t i = 0; i < decl.choices.size(); ++i)
        what += fmt::format("{}\"{}\"", i ? ", " : " ", decl.choices[i]);
      return what;
    }
    case KeyType::RealArray:
      what = fmt::format("an array of {} numbers", decl.array_size);
      break;
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
    out << "\n# " << s.doc << "\n[" << s.path << "]\n";
    for (const auto& k : keys_) {
      const auto dot = k.path.rfind('.');
      if (k.path.substr(0, dot) != s.path) continue;
      const std::string name = k.path.substr(dot + 1);
      out << "# " << k.doc << "\n# expected: " << describe_expected(k) << "\n";
      if (k.default_value)
        out << name << " = " << format_value(*k.default_value) << "\n";
      else
        out << "# " << name << " = ...   # required\n";
    }
  }
}

}  // namespace rcdem::io
