#pragma once
// Progress for long phases on stderr: a live line on a terminal, otherwise a line every few
// seconds; silent for phases that finish within a second, and when quiet.
#include <chrono>
#include <string>

namespace rcdem {

class Progress {
 public:
  Progress(std::string phase, bool quiet);
  ~Progress();
  void update(double fraction);  // in [0, 1]
  void done();

  static void set_quiet_default(bool quiet);
  static bool quiet_default();

 private:
  std::string phase_;
  bool quiet_;
  bool tty_;
  bool shown_ = false;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace rcdem
