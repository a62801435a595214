// Parsing of the initializer's guess (see pose_guess.h).
#include "hylo/localization/pose_guess.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace hylo::localization {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kMatrixTolerance = 1e-4;

Eigen::Isometry3d FromXyzRpyDeg(const std::vector<double>& v) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  T.linear() = (Eigen::AngleAxisd(v[5] * kDegToRad, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(v[4] * kDegToRad, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(v[3] * kDegToRad, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return T;
}

Eigen::Isometry3d FromRowMajor(const std::vector<double>& v) {
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) M(r, c) = v[4 * r + c];
  }
  const Eigen::RowVector4d last_row(0, 0, 0, 1);
  if ((M.row(3) - last_row).cwiseAbs().maxCoeff() > kMatrixTolerance) {
    std::ostringstream os;
    os << "pose guess: the 4x4 matrix's last row is [" << M.row(3) << "], expected [0 0 0 1]";
    throw std::invalid_argument(os.str());
  }
  const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  const double orthogonality = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  if (orthogonality > kMatrixTolerance || R.determinant() < 0.0) {
    std::ostringstream os;
    os << "pose guess: the 4x4 matrix's rotation block is not a rotation (|R^T R - I| = "
       << orthogonality << ", det = " << R.determinant() << ")";
    throw std::invalid_argument(os.str());
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(R).normalized().toRotationMatrix();
  T.translation() = M.topRightCorner<3, 1>();
  return T;
}

}  // namespace

Eigen::Isometry3d PoseGuessFromNumbers(const std::vector<double>& values) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw std::invalid_argument("pose guess: value " + std::to_string(i + 1) + " (" +
                                  std::to_string(values[i]) + ") is not finite");
    }
  }
  if (values.size() == 6) return FromXyzRpyDeg(values);
  if (values.size() == 16) return FromRowMajor(values);
  throw std::invalid_argument("pose guess: expected 6 numbers (x y z roll pitch yaw, m and "
                              "deg) or 16 (a 4x4 row-major matrix), got " +
                              std::to_string(values.size()));
}

Eigen::Isometry3d ParsePoseGuess(const std::string& text) {
  // The text is echoed in errors: on one line, whatever line breaks the user typed.
  std::string echoed = text;
  for (char& ch : echoed) {
    if (std::iscntrl(static_cast<unsigned char>(ch))) ch = ' ';
  }
  std::string spaced = text;
  for (char& ch : spaced) {
    if (ch == ',' || ch == ';' || ch == '\t' || ch == '[' || ch == ']') ch = ' ';
  }
  std::istringstream tokens(spaced);
  std::vector<double> values;
  std::string token;
  while (tokens >> token) {
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(value)) {
      throw std::invalid_argument("pose guess: value " + std::to_string(values.size() + 1) + " '" +
                                  token + "' is not a finite number (in '" + echoed + "')");
    }
    values.push_back(value);
  }
  return PoseGuessFromNumbers(values);
}

}  // namespace hylo::localization
