#include "rcdem/config/scenario_text.hpp"

#include <fstream>
#include <iterator>
#include <vector>

#include "rcdem/core/error.hpp"

namespace rcdem::config {

namespace fs = std::filesystem;

std::string read_scenario_file(const fs::path& path, const std::string& role,
                               const std::string& referrer) {
  const std::string who =
      referrer.empty() ? fmt::format("cannot read {} '{}'", role, path.string())
                       : fmt::format("{}: cannot read {} '{}'", referrer, role, path.string());
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows links: a link to a FIFO is a FIFO
  if (ec || !fs::exists(st)) fail("{}: no such file", who);
  if (fs::is_directory(st)) fail("{}: it is a directory, expected a TOML file", who);
  if (!fs::is_regular_file(st))
    fail("{}: not a regular file (a device, FIFO or socket), expected a TOML file", who);
  const auto size = fs::file_size(path, ec);
  if (ec) fail("{}: cannot read its size", who);
  if (size > kMaxScenarioBytes)
    fail("{}: {} bytes, more than the {} bytes a scenario file may have", who, size,
         kMaxScenarioBytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: permission denied or unreadable", who);
  // Read at most one byte past the cap: a file that grows while it is read is still bounded.
  std::string text;
  text.resize(kMaxScenarioBytes + 1);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) fail("{}: read error", who);
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > kMaxScenarioBytes)
    fail("{}: more than the {} bytes a scenario file may have", who, kMaxScenarioBytes);
  return text;
}

namespace {

// A lexical walk over TOML text that knows only what it needs: where strings and comments are
// (their brackets, dots and quotes do not count), where a key is being read (line start, after
// '{' or after ',' inside an inline table) and how deeply arrays and inline tables are open.
class NestingScan {
 public:
  NestingScan(const std::string& text, const std::string& source) : t_(text), source_(source) {}

  void run() {
    while (i_ < t_.size()) {
      const char c = t_[i_];
      if (c == '\n') {
        ++line_;
        ++i_;
        if (stack_.empty()) start_key(true);
      } else if (c == '#') {
        while (i_ < t_.size() && t_[i_] != '\n') ++i_;
      } else if (c == '"' || c == '\'') {
        skip_string(c);
        if (in_key_) seen_key_text_ = true;
      } else {
        punctuation(c);
        ++i_;
      }
    }
  }

 private:
  void start_key(bool at_line_start) {
    in_key_ = true;
    at_line_start_ = at_line_start;
    seen_key_text_ = false;
    key_dots_ = 0;
    in_header_ = false;
  }

  void punctuation(char c) {
    if (in_key_ || in_header_) {
      if (c == '.') {
        if (++key_dots_ + 1 > kMaxKeyDepth)
          fail(
              "{}:{}: a key or table header nested more than {} levels deep (rcdem's deepest "
              "key has 3)",
              source_, line_, kMaxKeyDepth);
      } else if (c == '[' && at_line_start_ && !seen_key_text_) {
        in_header_ = true;  // "[a.b]" or "[[a.b]]"
        in_key_ = false;
      } else if (c == ']' && in_header_) {
        in_header_ = false;
      } else if (c == '=' && in_key_) {
        in_key_ = false;
      } else if (c == '}' && in_key_ && !stack_.empty()) {
        close();  // "{}" or "{ a = 1, }"
      } else if (c != ' ' && c != '\t' && c != '\r') {
        seen_key_text_ = true;
      }
      return;
    }
    if (c == '[' || c == '{') {
      stack_.push_back(c);
      if (static_cast<int>(stack_.size()) > kMaxValueDepth)
        fail("{}:{}: arrays or inline tables nested more than {} levels deep", source_, line_,
             kMaxValueDepth);
      if (c == '{') start_key(false);
    } else if (c == ']' || c == '}') {
      close();
    } else if (c == ',' && !stack_.empty() && stack_.back() == '{') {
      start_key(false);
    }
  }

  void close() {
    if (!stack_.empty()) stack_.pop_back();
    in_key_ = false;
  }

  // Skips a basic ("..."), literal ('...') or multi-line ("""...""", '''...''') string from its
  // opening quote; a single-line string also ends at a newline (a syntax error left to toml++).
  void skip_string(char q) {
    const bool multi = t_.compare(i_, 3, std::string(3, q)) == 0;
    i_ += multi ? 3 : 1;
    while (i_ < t_.size()) {
      const char c = t_[i_];
      if (c == '\\' && q == '"') {
        i_ += 2;
        continue;
      }
      if (c == '\n') {
        if (!multi) return;
        ++line_;
      }
      if (c == q && (!multi || t_.compare(i_, 3, std::string(3, q)) == 0)) {
        i_ += multi ? 3 : 1;
        while (multi && i_ < t_.size() && t_[i_] == q) ++i_;  // """a""""": up to two more
        return;
      }
      ++i_;
    }
  }

  const std::string& t_;
  const std::string& source_;
  std::size_t i_ = 0;
  long line_ = 1;
  std::vector<char> stack_;
  bool in_key_ = true, at_line_start_ = true, seen_key_text_ = false, in_header_ = false;
  int key_dots_ = 0;
};

}  // namespace

void check_scenario_nesting(const std::string& text, const std::string& source) {
  NestingScan(text, source).run();
}

toml::table parse_scenario_toml(const std::string& text, const std::string& source) {
  check_scenario_nesting(text, source);
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    fail("{}:{}: TOML syntax error: {}", source, e.source().begin.line, e.description());
  }
}

}  // namespace rcdem::config
