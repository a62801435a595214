#pragma once
// The settings of the estimation back-end: which one (`backend`), what every back-end shares
// (`lidar_update`, `no_imu`, `robust_registration`, `standstill`) and each back-end's own
// section (`ieskf`, `sliding_window`). The member names are the configuration's section names,
// so a message from IsValid names the key a user wrote.

#include <string>

#include "hylo/estimation/estimator.h"
#include "hylo/estimation/ieskf/ieskf_options.h"
#include "hylo/estimation/lidar_update.h"
#include "hylo/estimation/no_imu_motion.h"
#include "hylo/estimation/robust_registration.h"
#include "hylo/estimation/sliding_window/sliding_window_options.h"
#include "hylo/estimation/standstill.h"

namespace hylo::estimation {

struct EstimatorOptions {
  Estimator::Backend backend = Estimator::Backend::kIeskf;  ///< `backend`
  LidarUpdateOptions lidar_update;      ///< the point-to-plane measurement, both back-ends
  NoImuOptions no_imu;                  ///< motion model and aids without an IMU, both back-ends
  /// Wide-basin alignment before the lidar update, both back-ends (off by default).
  RobustRegistrationOptions robust_registration;
  StandstillOptions standstill;         ///< zero-velocity updates at rest, both back-ends
  IeskfOptions ieskf;                   ///< used when backend == kIeskf
  SlidingWindowOptions sliding_window;  ///< used when backend == kSlidingWindow

  /// Every section, the unused back-end's too (a configuration is valid whichever it picks).
  bool IsValid(std::string* why) const;
};

}  // namespace hylo::estimation
