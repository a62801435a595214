#pragma once
// Progress of long C++ work, which runs without the GIL, handed to a Python callable (the
// package's bar, or the user's): at most ten times a second, taking the GIL only then. A
// pending signal (Ctrl-C) stops the work: the KeyboardInterrupt is thrown through it.

#include <pybind11/pybind11.h>

#include <chrono>
#include <cstddef>

namespace hylo::python {

namespace py = pybind11;

class ProgressRelay {
 public:
  /// `callback(done, total)`: total 0 when unknown; None reports nothing but still lets Ctrl-C
  /// through. Made and destroyed with the GIL held.
  explicit ProgressRelay(py::object callback) : callback_(std::move(callback)) {}

  /// Called by the work, without the GIL. `last` reports even within the interval.
  void operator()(std::size_t done, std::size_t total, bool last = false) {
    done_ = done;
    total_ = total;
    const auto now = std::chrono::steady_clock::now();
    if (!last && now - last_report_ < std::chrono::milliseconds(100)) return;
    last_report_ = now;
    Report();
  }

  /// Reports the last figures (the work ended between two reports). Without the GIL.
  void Flush() { Report(); }

 private:
  void Report() {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (!callback_.is_none()) callback_(done_, total_);
  }

  py::object callback_;
  std::size_t done_ = 0;
  std::size_t total_ = 0;
  std::chrono::steady_clock::time_point last_report_{};
};

}  // namespace hylo::python
