#pragma once
// A small recording for the log format tests: IMU at 200 Hz and Velodyne-layout scans at
// 10 Hz, written through any LogWriter, and the messages a reader gives compared exactly.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hylo/logs/log_reader.h"
#include "hylo/logs/log_writer.h"

namespace hylo::logs::testing {

constexpr int64_t kStartNs = 1700000000000000000;

/// `seconds` of messages in receive order (IMU at t, scans at their end), points varying.
inline std::vector<LogMessage> SampleMessages(double seconds, int points_per_scan = 50) {
  std::vector<LogMessage> messages;
  const int imu_count = static_cast<int>(seconds * 200);
  for (int i = 0; i <= imu_count; ++i) {
    const int64_t t = kStartNs + i * 5000000LL;
    if (i > 0 && i % 20 == 0) {  // a scan covering the last 0.1 s, received at its end
      LogMessage m;
      m.kind = LogMessage::Kind::kScan;
      m.scan.t_ns = t - 100000000;
      m.scan.frame_id = "lidar";
      for (int k = 0; k < points_per_scan; ++k) {
        ScanPoint p;
        p.position_lidar = {0.1f * k + 0.001f * i, 5.0f - 0.01f * k, -1.0f + 0.002f * i};
        p.intensity = static_cast<float>(k % 200);
        p.ring = static_cast<uint16_t>(k % 16);
        p.offset_ns = static_cast<int32_t>(k * (100000000 / points_per_scan));
        m.scan.points.push_back(p);
      }
      m.scan.end_t_ns = m.scan.t_ns + m.scan.points.back().offset_ns;
      messages.push_back(m);
    }
    LogMessage m;
    m.kind = LogMessage::Kind::kImu;
    m.imu.t_ns = t;
    m.imu.accel_imu = {0.01 * i, -0.02, 9.81};
    m.imu.gyro_imu = {0.001, 0.002 * (i % 7), -0.003};
    messages.push_back(m);
  }
  return messages;
}

inline void WriteMessages(const std::vector<LogMessage>& messages, LogWriter* writer) {
  for (const LogMessage& m : messages) {
    if (m.kind == LogMessage::Kind::kImu) {
      writer->WriteImu("/imu", m.imu, "imu");
    } else {
      writer->WriteScan("/points", m.scan, PointTimeConvention::kVelodyne, "lidar");
    }
  }
}

inline std::vector<LogMessage> ReadAll(LogReader* reader) {
  std::vector<LogMessage> messages;
  LogMessage m;
  while (reader->Next(&m)) messages.push_back(m);
  return messages;
}

inline std::vector<LogMessage> ReadAll(const std::string& path) {
  return ReadAll(OpenLog(path, LogReadOptions()).get());
}

/// The same messages, bit for bit (points, times, IMU values), in the same order.
inline void ExpectSameMessages(const std::vector<LogMessage>& a, const std::vector<LogMessage>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE("message " + std::to_string(i));
    ASSERT_EQ(a[i].kind, b[i].kind);
    if (a[i].kind == LogMessage::Kind::kImu) {
      EXPECT_EQ(a[i].imu.t_ns, b[i].imu.t_ns);
      EXPECT_EQ(a[i].imu.accel_imu, b[i].imu.accel_imu);
      EXPECT_EQ(a[i].imu.gyro_imu, b[i].imu.gyro_imu);
      continue;
    }
    const LidarScan& sa = a[i].scan;
    const LidarScan& sb = b[i].scan;
    EXPECT_EQ(sa.t_ns, sb.t_ns);
    EXPECT_EQ(sa.end_t_ns, sb.end_t_ns);
    ASSERT_EQ(sa.points.size(), sb.points.size());
    for (std::size_t k = 0; k < sa.points.size(); ++k) {
      EXPECT_EQ(sa.points[k].position_lidar, sb.points[k].position_lidar);
      EXPECT_EQ(sa.points[k].offset_ns, sb.points[k].offset_ns);
      EXPECT_EQ(sa.points[k].ring, sb.points[k].ring);
      EXPECT_EQ(sa.points[k].intensity, sb.points[k].intensity);
    }
  }
}

}  // namespace hylo::logs::testing
