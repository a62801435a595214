#pragma once
// A recorded log's messages as Python sees them (hylo.read_log): an IMU sample, or a scan
// whose points, times, intensities and rings are numpy views into the scan itself.

#include "hylo/common/sensor_data.h"

namespace hylo::python {

struct ImuMessage {
  ImuSample sample;
};

struct ScanMessage {
  LidarScan scan;
};

}  // namespace hylo::python
