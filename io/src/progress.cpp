#include "hylo/io/progress.h"

#include <unistd.h>

#include <cstdio>

namespace hylo::io {

Progress::Progress(std::string label, std::size_t total, bool enabled)
    : label_(std::move(label)),
      total_(total),
      tty_(isatty(fileno(stderr)) != 0),
      enabled_(enabled),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

Progress::~Progress() { Finish(); }

double Progress::ElapsedSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::Update(std::size_t done) {
  done_ = done;
  const auto now = std::chrono::steady_clock::now();
  if (tty_) {
    if (now - last_print_ < std::chrono::milliseconds(200)) return;
    last_print_ = now;
    Print(done, false);
    return;
  }
  if (total_ == 0) {
    if (now - last_print_ < std::chrono::seconds(5)) return;
    last_print_ = now;
    Print(done, false);
    return;
  }
  const int decile = static_cast<int>(10 * done / total_);
  if (decile > last_decile_) {
    last_decile_ = decile;
    Print(done, false);
  }
}

void Progress::Finish() {
  if (finished_) return;
  finished_ = true;
  // Without a terminal the 100 % line may already be printed; do not repeat it.
  if (!tty_ && total_ > 0 && last_decile_ == 10 && done_ == total_) return;
  Print(done_, true);
}

void Progress::Print(std::size_t done, bool final_line) {
  if (!enabled_) return;
  const double elapsed = ElapsedSeconds();
  if (total_ > 0) {
    std::fprintf(stderr, "%s[%s] %zu/%zu (%3.0f%%) %.1f s%s", tty_ ? "\r" : "", label_.c_str(),
                 done, total_, 100.0 * done / total_, elapsed,
                 (final_line || !tty_) ? "\n" : "");
  } else {
    std::fprintf(stderr, "%s[%s] %zu %.1f s%s", tty_ ? "\r" : "", label_.c_str(), done, elapsed,
                 (final_line || !tty_) ? "\n" : "");
  }
  std::fflush(stderr);
}

}  // namespace hylo::io
