#include "hylo/odometry/scan_result.h"

namespace hylo::odometry {

const char* ToString(PoseStatus status) {
  switch (status) {
    case PoseStatus::kValid:
      return "valid";
    case PoseStatus::kLost:
      return "lost";
    case PoseStatus::kProvisional:
      return "provisional";
  }
  return "unknown";
}

}  // namespace hylo::odometry
