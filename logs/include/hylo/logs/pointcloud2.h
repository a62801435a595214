#pragma once
// sensor_msgs/PointCloud2 <-> LidarScan, written here (no pcl_conversions). The message is
// mirrored in plain C++ types so that no ROS header reaches hylo's public interface; the bag
// reader and writer move the bytes between this mirror and the ROS message without copying.
//
// Field layouts of the drivers handled (kAuto detects them from the field names):
//   Velodyne  velodyne_pointcloud PointcloudXYZIRT: x y z intensity f32, ring u16, time f32
//             (seconds after the scan stamp); point_step 22, fields packed.
//   Ouster    ouster-ros ouster_ros::Point (PCL, EIGEN_ALIGN16): x y z f32 @0/4/8,
//             intensity f32 @16, t u32 (ns after the scan stamp) @20, reflectivity u16 @24,
//             ring u16 @26 (u8 in the older ouster_example driver), ambient u16 @28,
//             range u32 (mm) @32; point_step 48.
//   Hesai     HesaiLidar_ROS_2.0: x y z intensity f32, ring u16 @16, timestamp f64 @18
//             (absolute seconds); point_step 26; header.stamp = first point.
//   Robosense rslidar_sdk XYZIRT: the same bytes as Hesai; header.stamp = last point
//             (rs_driver's ts_first_point defaults to false).
//   Livox     livox_ros_driver2 (xfer_format 0): x y z intensity f32, tag u8 @16, line u8
//             @17, timestamp f64 @18 (absolute *nanoseconds*: the packet time plus i times
//             the point interval, in ns); point_step 26; header.stamp = first point.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/common/sensor_data.h"
#include "hylo/logs/log_reader.h"

namespace hylo::logs {

/// sensor_msgs/PointField datatype codes (the values of the ROS message constants).
enum PointFieldDatatype : uint8_t {
  kInt8 = 1,
  kUint8 = 2,
  kInt16 = 3,
  kUint16 = 4,
  kInt32 = 5,
  kUint32 = 6,
  kFloat32 = 7,
  kFloat64 = 8,
};

/// Size in bytes of one element of `datatype`; 0 for an unknown code.
std::size_t PointFieldSize(uint8_t datatype);
/// "float32", "uint16", ... ; "unknown(<code>)" for an unknown code.
std::string PointFieldDatatypeName(uint8_t datatype);

/// One sensor_msgs/PointField.
struct PointFieldInfo {
  std::string name;      ///< field name ("x", "time", ...)
  uint8_t datatype = 0;  ///< a PointFieldDatatype code
  uint32_t offset = 0;   ///< byte offset inside a point
  uint32_t count = 1;    ///< elements in the field (only the first one is read)
};

/// A sensor_msgs/PointCloud2 message in plain C++ types.
struct PointCloud2Message {
  int64_t stamp_ns = 0;       ///< header.stamp, ns
  std::string frame_id;       ///< header.frame_id
  uint32_t height = 1;        ///< rows (1 for an unorganized cloud)
  uint32_t width = 0;         ///< points per row
  std::vector<PointFieldInfo> fields;
  bool is_bigendian = false;  ///< byte order of `data`
  uint32_t point_step = 0;    ///< bytes per point
  uint32_t row_step = 0;      ///< bytes per row (>= width * point_step)
  std::vector<uint8_t> data;  ///< height * row_step bytes
  bool is_dense = false;      ///< true when no point is invalid
};

/// The per-point time convention that the field names announce: `t` -> Ouster, `time` ->
/// Velodyne, `timestamp` with `line` or `tag` -> Livox, `timestamp` -> Hesai (Robosense
/// writes the same bytes and meaning, so the two decode alike), none of these -> kNone.
PointTimeConvention DetectPointTimeConvention(const std::vector<PointFieldInfo>& fields);

/// Decodes a cloud into a scan. `convention` kAuto detects it from the fields.
/// Relative conventions: t_ns = header.stamp (or the earliest point when a driver wrote
/// negative offsets, so that offsets stay >= 0). Absolute ones: t_ns = the earliest point.
/// end_t_ns = the latest point (t_ns for an empty scan). Points with a NaN/inf coordinate
/// or time are dropped; their number is added to `*dropped_non_finite` (may be null).
/// `ring` comes from a `ring` field, else from `line` (Livox); intensity from `intensity`;
/// both 0 when absent. Big-endian clouds are byte-swapped.
/// Throws std::runtime_error with a one-line reason (no file name: callers add it) on a
/// malformed layout, missing x/y/z, a missing time field for an explicit convention, or
/// per-point times spanning more than an int32 of nanoseconds.
LidarScan DecodePointCloud2(const PointCloud2Message& cloud, PointTimeConvention convention,
                            std::size_t* dropped_non_finite);

/// Encodes a scan in the field layout of the driver of `layout` (see the file comment;
/// kNone writes x y z intensity f32, point_step 16). header.stamp = scan start, except
/// Robosense (last point) as its driver does. Little-endian, height 1, is_dense true when
/// every point is finite. `layout` must not be kAuto; Livox needs ring <= 255.
PointCloud2Message EncodePointCloud2(const LidarScan& scan, PointTimeConvention layout);

}  // namespace hylo::logs
