#pragma once
// Progress for long work, on stderr: a live line on a terminal, a line every 10 % otherwise
// (logs and CI stay readable). Library code reports progress through a callback; only apps
// print.

#include <chrono>
#include <cstddef>
#include <string>

namespace hylo::io {

class Progress {
 public:
  /// `total` = 0 means unknown: the count is shown without a percentage. `enabled` = false
  /// prints nothing (the elapsed time is still measured).
  Progress(std::string label, std::size_t total, bool enabled = true);
  ~Progress();

  /// Reports `done` items finished. Cheap to call per item: prints at most ~5 times a second.
  void Update(std::size_t done);
  /// Prints the final line with the elapsed time (called by the destructor if not before).
  void Finish();

  double ElapsedSeconds() const;

 private:
  void Print(std::size_t done, bool final_line);

  std::string label_;
  std::size_t total_;
  std::size_t done_ = 0;
  bool tty_;
  bool enabled_;
  bool finished_ = false;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_print_;
};

}  // namespace hylo::io
