// Fuzz target: the ICP initializer's pose guess as a user writes it (`--guess`, the YAML
// string) through ParsePoseGuess; with an odd first byte, the rest as raw doubles through
// PoseGuessFromNumbers (the YAML list form).

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "hylo/localization/pose_guess.h"

namespace {

void CheckPose(const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d R = T.linear();
  hylo::fuzz::Require(T.translation().allFinite(), "non-finite translation accepted");
  hylo::fuzz::Require((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-9 &&
                          std::abs(R.determinant() - 1.0) < 1e-9,
                      "the guess's rotation is not a rotation");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  try {
    if (data[0] % 2 == 0) {
      CheckPose(hylo::localization::ParsePoseGuess(
          std::string(reinterpret_cast<const char*>(data + 1), size - 1)));
    } else {
      std::vector<double> values((size - 1) / sizeof(double));
      if (!values.empty()) std::memcpy(values.data(), data + 1, values.size() * sizeof(double));
      CheckPose(hylo::localization::PoseGuessFromNumbers(values));
    }
  } catch (const std::invalid_argument& e) {
    hylo::fuzz::RequireClearError(e, "pose guess");
  }
  return 0;
}
