#pragma once
// Declared, validated configuration (in the manner of deal.II's ParameterHandler): every scenario
// key is declared once with its type, default, admissible range, unit and a doc line. The loader
// rejects unknown keys and bad values with file, line and what was expected, and print-schema
// turns the same declarations into a documented template, so the docs cannot drift from the code.
#include <cstdint>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

namespace rcdem::config {

enum class KeyType { Real, Integer, Boolean, String, RealArray, StringArray };

using Value = std::variant<double, std::int64_t, bool, std::string, std::vector<double>,
                           std::vector<std::string>>;

struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;
};

struct KeyDecl {
  std::string path;  // dotted: "generation.aggregate.d_min"
  KeyType type = KeyType::Real;
  std::optional<Value> default_value;  // none: the key is required
  Range range;                         // for Real, Integer and each RealArray element
  std::vector<std::string> choices;    // for String: the admissible values
  int array_size = 0;                  // for RealArray: the exact length
  int array_step = 0;  // for RealArray: instead, any multiple of this, at least two of them
  std::string unit;                    // SI unit, "" for dimensionless
  std::string doc;
};

struct SectionDecl {
  std::string path;  // "generation.aggregate"
  std::string doc;
};

class Schema {
 public:
  Schema& section(std::string path, std::string doc);
  Schema& key(KeyDecl decl);

  const KeyDecl* find_key(const std::string& path) const;
  bool is_section(const std::string& path) const;
  const std::vector<KeyDecl>& keys() const { return keys_; }
  const std::vector<SectionDecl>& sections() const { return sections_; }
  std::vector<std::string> keys_in_section(const std::string& section) const;

  // A TOML template with every key, its default (required keys commented), unit, range and doc.
  void print_template(std::ostream& out) const;

  // "a positive length in m", "one of \"box\", \"beam\"", ... for error messages.
  static std::string describe_expected(const KeyDecl& decl);

 private:
  std::vector<SectionDecl> sections_;
  std::vector<KeyDecl> keys_;
};

std::string format_value(const Value& value);

// Whether a declared path (where a '*' segment matches any one name) matches a concrete path.
bool path_matches(const std::string& pattern, const std::string& path);

// The schema of rcdem's scenario files (declared in scenario_schema.cpp).
const Schema& scenario_schema();

}  // namespace rcdem::config
