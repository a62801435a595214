// The drivers' PointCloud2 field layouts: detection from field names, and encoding of a
// LidarScan in a chosen driver's layout (what the simulator writes, what tests round-trip).

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include "hylo/common/check.h"
#include "hylo/logs/pointcloud2.h"

namespace hylo::logs {

std::size_t PointFieldSize(uint8_t datatype) {
  switch (datatype) {
    case kInt8:
    case kUint8: return 1;
    case kInt16:
    case kUint16: return 2;
    case kInt32:
    case kUint32:
    case kFloat32: return 4;
    case kFloat64: return 8;
    default: return 0;
  }
}

std::string PointFieldDatatypeName(uint8_t datatype) {
  switch (datatype) {
    case kInt8: return "int8";
    case kUint8: return "uint8";
    case kInt16: return "int16";
    case kUint16: return "uint16";
    case kInt32: return "int32";
    case kUint32: return "uint32";
    case kFloat32: return "float32";
    case kFloat64: return "float64";
    default: return "unknown(" + std::to_string(datatype) + ")";
  }
}

PointTimeConvention DetectPointTimeConvention(const std::vector<PointFieldInfo>& fields) {
  auto has = [&fields](const char* name) {
    for (const auto& f : fields) {
      if (f.name == name) return true;
    }
    return false;
  };
  if (has("t")) return PointTimeConvention::kOuster;
  if (has("time")) return PointTimeConvention::kVelodyne;
  if (has("timestamp")) {
    // livox_ros_driver2 is the only one of these drivers with `tag`/`line`; its timestamp is
    // in ns, where Hesai's and Robosense's are in seconds.
    return (has("line") || has("tag")) ? PointTimeConvention::kLivox
                                       : PointTimeConvention::kHesai;
  }
  return PointTimeConvention::kNone;
}

namespace {

/// What a field of an encoded point holds.
enum class Role { kX, kY, kZ, kIntensity, kRing, kZero, kOffsetSeconds, kOffsetNs,
                  kAbsoluteSeconds, kAbsoluteNs, kRangeMm };

struct FieldSpec {
  const char* name;
  uint8_t datatype;
  uint32_t offset;
  Role role;
};

struct DriverLayout {
  std::vector<FieldSpec> fields;
  uint32_t point_step = 0;
};

// Offsets as each driver writes them (see hylo/io/pointcloud2.h for the sources).
DriverLayout LayoutFor(PointTimeConvention layout) {
  const std::vector<FieldSpec> xyzi = {{"x", kFloat32, 0, Role::kX},
                                       {"y", kFloat32, 4, Role::kY},
                                       {"z", kFloat32, 8, Role::kZ},
                                       {"intensity", kFloat32, 12, Role::kIntensity}};
  DriverLayout out{xyzi, 16};
  switch (layout) {
    case PointTimeConvention::kVelodyne:
      out.fields.push_back({"ring", kUint16, 16, Role::kRing});
      out.fields.push_back({"time", kFloat32, 18, Role::kOffsetSeconds});
      out.point_step = 22;
      break;
    case PointTimeConvention::kOuster:
      // PCL struct with 16-byte aligned x y z (+ padding): intensity starts at 16.
      out.fields = {{"x", kFloat32, 0, Role::kX},
                    {"y", kFloat32, 4, Role::kY},
                    {"z", kFloat32, 8, Role::kZ},
                    {"intensity", kFloat32, 16, Role::kIntensity},
                    {"t", kUint32, 20, Role::kOffsetNs},
                    {"reflectivity", kUint16, 24, Role::kZero},
                    {"ring", kUint16, 26, Role::kRing},
                    {"ambient", kUint16, 28, Role::kZero},
                    {"range", kUint32, 32, Role::kRangeMm}};
      out.point_step = 48;
      break;
    case PointTimeConvention::kHesai:
    case PointTimeConvention::kRobosense:
      out.fields.push_back({"ring", kUint16, 16, Role::kRing});
      out.fields.push_back({"timestamp", kFloat64, 18, Role::kAbsoluteSeconds});
      out.point_step = 26;
      break;
    case PointTimeConvention::kLivox:
      out.fields.push_back({"tag", kUint8, 16, Role::kZero});
      out.fields.push_back({"line", kUint8, 17, Role::kRing});
      out.fields.push_back({"timestamp", kFloat64, 18, Role::kAbsoluteNs});
      out.point_step = 26;
      break;
    case PointTimeConvention::kNone: break;
    case PointTimeConvention::kAuto: HYLO_CHECK(false, "kAuto is not a layout to write");
  }
  return out;
}

/// Absolute seconds as the nearest double: whole seconds and the fraction added separately.
double NsToSeconds(int64_t t_ns) {
  const int64_t whole = t_ns / 1000000000;
  return static_cast<double>(whole) + static_cast<double>(t_ns - whole * 1000000000) * 1e-9;
}

double FieldValue(Role role, const ScanPoint& p, int64_t scan_t_ns) {
  switch (role) {
    case Role::kX: return p.position_lidar.x();
    case Role::kY: return p.position_lidar.y();
    case Role::kZ: return p.position_lidar.z();
    case Role::kIntensity: return p.intensity;
    case Role::kRing: return p.ring;
    case Role::kZero: return 0.0;
    case Role::kOffsetSeconds: return p.offset_ns * 1e-9;
    case Role::kOffsetNs: return p.offset_ns;
    case Role::kAbsoluteSeconds: return NsToSeconds(scan_t_ns + p.offset_ns);
    case Role::kAbsoluteNs: return static_cast<double>(scan_t_ns + p.offset_ns);
    case Role::kRangeMm: return std::round(p.position_lidar.cast<double>().norm() * 1000.0);
  }
  return 0.0;
}

template <typename T>
void Store(double value, uint8_t* bytes) {
  if constexpr (std::is_integral_v<T>) {  // NaN or out-of-range -> defined integer values
    value = std::isfinite(value) ? std::clamp<double>(std::round(value),
                                                      std::numeric_limits<T>::lowest(),
                                                      std::numeric_limits<T>::max())
                                 : 0.0;
  }
  const T v = static_cast<T>(value);
  std::memcpy(bytes, &v, sizeof(T));
}

/// Writes `value` as `datatype` (little-endian host assumed, as on every supported target).
void WriteScalar(double value, uint8_t datatype, uint8_t* bytes) {
  switch (datatype) {
    case kInt8: Store<int8_t>(value, bytes); break;
    case kUint8: Store<uint8_t>(value, bytes); break;
    case kInt16: Store<int16_t>(value, bytes); break;
    case kUint16: Store<uint16_t>(value, bytes); break;
    case kInt32: Store<int32_t>(value, bytes); break;
    case kUint32: Store<uint32_t>(value, bytes); break;
    case kFloat32: Store<float>(value, bytes); break;
    case kFloat64: Store<double>(value, bytes); break;
    default: HYLO_CHECK(false, "unknown datatype");
  }
}

}  // namespace

PointCloud2Message EncodePointCloud2(const LidarScan& scan, PointTimeConvention layout) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "encoder writes host byte order");
  const DriverLayout driver = LayoutFor(layout);
  PointCloud2Message cloud;
  cloud.stamp_ns = layout == PointTimeConvention::kRobosense ? scan.end_t_ns : scan.t_ns;
  cloud.frame_id = scan.frame_id;
  cloud.height = 1;
  cloud.width = static_cast<uint32_t>(scan.points.size());
  for (const auto& f : driver.fields) cloud.fields.push_back({f.name, f.datatype, f.offset, 1});
  cloud.point_step = driver.point_step;
  cloud.row_step = cloud.width * cloud.point_step;
  cloud.data.assign(std::size_t{cloud.row_step}, 0);
  cloud.is_dense = true;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    const ScanPoint& p = scan.points[i];
    HYLO_CHECK(layout != PointTimeConvention::kLivox || p.ring <= 255,
               "Livox `line` is uint8; ring must be <= 255");
    cloud.is_dense = cloud.is_dense && p.position_lidar.allFinite();
    uint8_t* bytes = cloud.data.data() + i * cloud.point_step;
    for (const auto& f : driver.fields) {
      WriteScalar(FieldValue(f.role, p, scan.t_ns), f.datatype, bytes + f.offset);
    }
  }
  return cloud;
}

}  // namespace hylo::logs
