#include "guess.h"

#include <pybind11/numpy.h>

#include <cstdio>

#include "hylo/localization/pose_guess.h"

namespace hylo::python {
namespace {

// Numbers as the text a user would pass to --guess; %.17g reads back to the same doubles.
std::string GuessText(const py::handle& guess) {
  if (py::isinstance<py::str>(guess)) return guess.cast<std::string>();
  const auto numbers = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(guess);
  if (!numbers) {
    PyErr_Clear();
    throw std::invalid_argument(
        "guess: expected \"x y z roll pitch yaw\" (m, deg), 6 numbers or a 4x4 matrix");
  }
  std::string text;
  const double* values = numbers.data();
  for (py::ssize_t i = 0; i < numbers.size(); ++i) {
    char number[32];
    std::snprintf(number, sizeof(number), "%.17g", values[i]);
    text += (i > 0 ? " " : "") + std::string(number);
  }
  return text;
}

}  // namespace

std::optional<Eigen::Isometry3d> ResolveGuess(const py::handle& guess, config::RunConfig* config) {
  const std::string given = guess.is_none() ? std::string() : GuessText(guess);
  const std::string text = given.empty() ? config->initial_guess : given;
  if (text.empty() && !config->pipeline.localization.global_enabled) {
    throw std::invalid_argument(
        "no initial guess and localization.global_enabled is false: pass guess=\"x y z roll "
        "pitch yaw\" or set localization.initial_guess in the configuration");
  }
  config->initial_guess = text;  // saved with the effective configuration
  if (text.empty()) return std::nullopt;
  return localization::ParsePoseGuess(text);
}

}  // namespace hylo::python
