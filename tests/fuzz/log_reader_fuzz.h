#pragma once
// What every log reader promises about the scans and samples it yields, whatever the format:
// shared by the ROS1 bag and ROS 2 recording targets.

#include "fuzz_support.h"
#include "hylo/logs/log_reader.h"

namespace hylo::fuzz {

/// Reads `reader` to its end and checks each message it delivers.
inline void CheckLogMessages(logs::LogReader& reader) {
  logs::LogMessage m;
  while (reader.Next(&m)) {
    if (m.kind == logs::LogMessage::Kind::kImu) {
      Require(m.imu.accel_imu.allFinite() && m.imu.gyro_imu.allFinite(),
              "a non-finite IMU sample was delivered");
      continue;
    }
    Require(m.scan.t_ns <= m.scan.end_t_ns, "scan ends before it starts");
    for (const hylo::ScanPoint& p : m.scan.points) {
      Require(p.position_lidar.allFinite(), "a non-finite point was kept");
      Require(p.offset_ns >= 0 && p.offset_ns <= m.scan.end_t_ns - m.scan.t_ns,
              "a point's time offset lies outside [t_ns, end_t_ns]");
    }
  }
}

}  // namespace hylo::fuzz
