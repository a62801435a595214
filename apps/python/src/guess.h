#pragma once
// The start pose of a localization as Python gives it: None, the command line's text
// ("x y z roll pitch yaw", 16 numbers) or numbers (6, or a 4×4 matrix), resolved against the
// configuration's localization.initial_guess exactly as `hylo localize --guess` is.

#include <pybind11/pybind11.h>

#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "hylo/config/run_config.h"

namespace hylo::python {

namespace py = pybind11;

/// The guess to start from (none: a global search). Sets config->initial_guess to the text
/// used, as a run saves it. Throws std::invalid_argument: a malformed guess, or none while
/// localization.global_enabled is false.
std::optional<Eigen::Isometry3d> ResolveGuess(const py::handle& guess, config::RunConfig* config);

}  // namespace hylo::python
