// Parsing of the initializer's guess: both forms, separators, and errors naming the value.
#include "hylo/localization/pose_guess.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hylo::localization {
namespace {

std::string ErrorOf(const std::string& text) {
  try {
    ParsePoseGuess(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(PoseGuess, XyzRollPitchYawInDegrees) {
  const Eigen::Isometry3d T = ParsePoseGuess("1.5 -2 0.25 0 0 90");
  EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(1.5, -2, 0.25)));
  // Yaw 90 deg: body x points along map y.
  EXPECT_LT((T.linear() * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  // ZYX order: R = Rz(yaw) Ry(pitch) Rx(roll).
  const Eigen::Isometry3d U = ParsePoseGuess("[0, 0, 0, 10, 20, 30]");
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(30 * M_PI / 180, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(20 * M_PI / 180, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(10 * M_PI / 180, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  EXPECT_LT((U.linear() - R).norm(), 1e-12);
}

TEST(PoseGuess, RowMajorMatrix) {
  const Eigen::Isometry3d T =
      ParsePoseGuess("0 -1 0 500000.5\n1 0 0 4200000.25\n0 0 1 12\n0 0 0 1");
  EXPECT_EQ(T.translation().x(), 500000.5);  // UTM-sized values keep their digits
  EXPECT_EQ(T.translation().y(), 4200000.25);
  EXPECT_LT((T.linear() * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  EXPECT_TRUE(PoseGuessFromNumbers({1, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1})
                  .translation()
                  .isApprox(Eigen::Vector3d(1, 2, 3)));
}

TEST(PoseGuess, ErrorsNameTheBadValue) {
  EXPECT_NE(ErrorOf("1 2 abc 0 0 0").find("value 3 'abc'"), std::string::npos);
  EXPECT_NE(ErrorOf("1 2 3 0 0 nan").find("value 6 'nan'"), std::string::npos);
  EXPECT_NE(ErrorOf("1 2 3 0 0").find("got 5"), std::string::npos);
  EXPECT_NE(ErrorOf("").find("got 0"), std::string::npos);
  EXPECT_NE(ErrorOf("1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1").find("last row"), std::string::npos);
  EXPECT_NE(ErrorOf("2 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1").find("not a rotation"),
            std::string::npos);
  EXPECT_NE(ErrorOf("-1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1").find("det = -1"), std::string::npos);
}

}  // namespace
}  // namespace hylo::localization
