#pragma once
// The initial guess of the ICP initializer as a user writes it, on the command line
// (`--guess "x y z roll pitch yaw"`) or in the YAML configuration (a string or a list of
// numbers). Kept here, below estimation/ and apps/, so both the CLI and the YAML reader reach
// the same parser.

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace hylo::localization {

/// From numbers: 6 = x y z (m) roll pitch yaw (deg), R = Rz(yaw) Ry(pitch) Rx(roll) (the
/// map-from-body ZYX convention); 16 = a 4x4 homogeneous matrix, row-major, whose last row
/// must be 0 0 0 1 and whose rotation block must be orthonormal with determinant +1 (within
/// 1e-4; it is then re-orthonormalised). Throws std::invalid_argument naming the count or the
/// offending value.
Eigen::Isometry3d PoseGuessFromNumbers(const std::vector<double>& values);

/// Parses 6 or 16 numbers separated by spaces, tabs, commas or semicolons (brackets are
/// ignored, so "[1, 2, 3, 0, 0, 90]" works). Throws std::invalid_argument naming the token
/// that is not a finite number (and its position), or the wrong count.
Eigen::Isometry3d ParsePoseGuess(const std::string& text);

}  // namespace hylo::localization
