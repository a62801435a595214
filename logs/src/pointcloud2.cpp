// Decoding of sensor_msgs/PointCloud2 (mirrored in PointCloud2Message) into a LidarScan.
// Field layouts of the drivers: see hylo/io/pointcloud2.h.

#include "hylo/logs/pointcloud2.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "printable.h"

namespace hylo::logs {
namespace {

using detail::Printable;

constexpr bool kHostIsBigEndian = __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__;

/// How a convention stores the time of a return.
enum class TimeKind { kNone, kRelativeSeconds, kRelativeNs, kAbsoluteSeconds, kAbsoluteNs };

struct TimeSpec {
  TimeKind kind = TimeKind::kNone;
  const char* field = "";
};

TimeSpec TimeSpecFor(PointTimeConvention convention) {
  switch (convention) {
    case PointTimeConvention::kVelodyne: return {TimeKind::kRelativeSeconds, "time"};
    case PointTimeConvention::kOuster: return {TimeKind::kRelativeNs, "t"};
    case PointTimeConvention::kHesai:
    case PointTimeConvention::kRobosense: return {TimeKind::kAbsoluteSeconds, "timestamp"};
    case PointTimeConvention::kLivox: return {TimeKind::kAbsoluteNs, "timestamp"};
    case PointTimeConvention::kAuto:
    case PointTimeConvention::kNone: break;
  }
  return {};
}

/// Where one field lives in a point; `datatype` 0 = absent.
struct FieldSlot {
  uint8_t datatype = 0;
  uint32_t offset = 0;
  bool present() const { return datatype != 0; }
};

struct PointReaders {
  FieldSlot x, y, z, intensity, ring, time;
  TimeKind time_kind = TimeKind::kNone;
};

std::string FieldList(const std::vector<PointFieldInfo>& fields) {
  std::ostringstream os;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    os << (i ? ", " : "") << Printable(fields[i].name) << ':'
       << PointFieldDatatypeName(fields[i].datatype);
  }
  return fields.empty() ? std::string("none") : os.str();
}

FieldSlot FindField(const std::vector<PointFieldInfo>& fields, const std::string& name) {
  for (const auto& f : fields) {
    if (f.name == name) return {f.datatype, f.offset};
  }
  return {};
}

/// Throws when the layout cannot be read safely: unknown datatypes, fields past point_step,
/// rows shorter than width * point_step, or fewer bytes than the rows need.
void CheckLayout(const PointCloud2Message& cloud) {
  const uint64_t num_points = uint64_t{cloud.width} * cloud.height;
  for (const auto& f : cloud.fields) {
    const std::size_t size = PointFieldSize(f.datatype);
    if (size == 0) {
      throw std::runtime_error("field '" + Printable(f.name) + "' has unknown datatype " +
                               std::to_string(f.datatype));
    }
    const uint64_t end = uint64_t{f.offset} + size * std::max<uint32_t>(f.count, 1);
    if (num_points > 0 && end > cloud.point_step) {
      throw std::runtime_error("field '" + Printable(f.name) + "' ends at byte " +
                               std::to_string(end) + ", past point_step " +
                               std::to_string(cloud.point_step));
    }
  }
  if (num_points == 0) return;
  if (uint64_t{cloud.row_step} < uint64_t{cloud.width} * cloud.point_step) {
    throw std::runtime_error("row_step " + std::to_string(cloud.row_step) +
                             " is less than width * point_step");
  }
  const uint64_t needed =
      uint64_t{cloud.row_step} * (cloud.height - 1) + uint64_t{cloud.width} * cloud.point_step;
  if (cloud.data.size() < needed) {
    throw std::runtime_error("data holds " + std::to_string(cloud.data.size()) +
                             " bytes, the layout needs " + std::to_string(needed));
  }
}

PointReaders BindFields(const PointCloud2Message& cloud, PointTimeConvention convention) {
  PointReaders r;
  r.x = FindField(cloud.fields, "x");
  r.y = FindField(cloud.fields, "y");
  r.z = FindField(cloud.fields, "z");
  if (!r.x.present() || !r.y.present() || !r.z.present()) {
    throw std::runtime_error("PointCloud2 has no x/y/z fields (fields: " +
                             FieldList(cloud.fields) + ")");
  }
  r.intensity = FindField(cloud.fields, "intensity");
  r.ring = FindField(cloud.fields, "ring");
  if (!r.ring.present()) r.ring = FindField(cloud.fields, "line");  // Livox
  const TimeSpec spec = TimeSpecFor(convention);
  r.time_kind = spec.kind;
  if (spec.kind != TimeKind::kNone) {
    r.time = FindField(cloud.fields, spec.field);
    if (!r.time.present()) {
      throw std::runtime_error("per-point time convention needs a field '" +
                               std::string(spec.field) + "' (fields: " +
                               FieldList(cloud.fields) + ")");
    }
  }
  return r;
}

template <typename T>
double Load(const uint8_t* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return static_cast<double>(value);
}

/// Reads one element of any PointField datatype as a double (exact for every integer type
/// up to 32 bits), swapping bytes when the cloud's byte order differs from the host's.
double ReadScalar(const uint8_t* point, const FieldSlot& slot, bool swap) {
  uint8_t bytes[8];
  const std::size_t size = PointFieldSize(slot.datatype);
  std::memcpy(bytes, point + slot.offset, size);
  if (swap) std::reverse(bytes, bytes + size);
  switch (slot.datatype) {
    case kInt8: return Load<int8_t>(bytes);
    case kUint8: return Load<uint8_t>(bytes);
    case kInt16: return Load<int16_t>(bytes);
    case kUint16: return Load<uint16_t>(bytes);
    case kInt32: return Load<int32_t>(bytes);
    case kUint32: return Load<uint32_t>(bytes);
    case kFloat32: return Load<float>(bytes);
    case kFloat64: return Load<double>(bytes);
    default: return std::numeric_limits<double>::quiet_NaN();
  }
}

constexpr double kMaxNs = 9.0e18;  // inside int64, with margin for the additions below

/// Converts a stored time value to absolute ns; false for NaN/inf or out-of-range values.
bool ToAbsoluteNs(double value, TimeKind kind, int64_t stamp_ns, int64_t* t_ns) {
  if (!std::isfinite(value)) return false;
  switch (kind) {
    case TimeKind::kNone: *t_ns = stamp_ns; return true;
    case TimeKind::kRelativeSeconds: value *= 1e9; break;
    case TimeKind::kRelativeNs:
    case TimeKind::kAbsoluteNs: break;
    case TimeKind::kAbsoluteSeconds: {
      // Whole and fractional seconds apart: value * 1e9 would round to 256 ns near 1.7e18.
      const double whole = std::floor(value);
      if (std::abs(whole) > kMaxNs / 1e9) return false;
      *t_ns = static_cast<int64_t>(whole) * 1000000000 + std::llround((value - whole) * 1e9);
      return true;
    }
  }
  const bool relative = kind == TimeKind::kRelativeSeconds || kind == TimeKind::kRelativeNs;
  // The offset and the time it gives (offset + stamp) must both stay inside int64.
  if (std::abs(value) > kMaxNs) return false;
  if (relative && std::abs(value + static_cast<double>(stamp_ns)) > kMaxNs) return false;
  *t_ns = std::llround(value) + (relative ? stamp_ns : 0);
  return true;
}

/// Sets t_ns, end_t_ns and the per-point offsets from the absolute point times.
void AssignTimes(int64_t stamp_ns, TimeKind kind, const std::vector<int64_t>& times_ns,
                 LidarScan* scan) {
  scan->t_ns = stamp_ns;
  scan->end_t_ns = stamp_ns;
  if (times_ns.empty()) return;
  const auto [min_it, max_it] = std::minmax_element(times_ns.begin(), times_ns.end());
  const bool relative = kind != TimeKind::kAbsoluteSeconds && kind != TimeKind::kAbsoluteNs;
  scan->t_ns = relative ? std::min(stamp_ns, *min_it) : *min_it;
  scan->end_t_ns = std::max(scan->t_ns, *max_it);
  // Roughly in double first (times near both ends of int64 would overflow the subtraction),
  // then exactly.
  const double approx_span_ns = static_cast<double>(scan->end_t_ns) - scan->t_ns;
  if (approx_span_ns > 4e9 || scan->end_t_ns - scan->t_ns > std::numeric_limits<int32_t>::max()) {
    throw std::runtime_error("per-point times span " + std::to_string(approx_span_ns * 1e-9) +
                             " s, more than an int32 of ns offsets holds (wrong convention?)");
  }
  for (std::size_t i = 0; i < times_ns.size(); ++i) {
    scan->points[i].offset_ns = static_cast<int32_t>(times_ns[i] - scan->t_ns);
  }
}

}  // namespace

LidarScan DecodePointCloud2(const PointCloud2Message& cloud, PointTimeConvention convention,
                            std::size_t* dropped_non_finite) {
  CheckLayout(cloud);
  if (convention == PointTimeConvention::kAuto) {
    convention = DetectPointTimeConvention(cloud.fields);
  }
  const PointReaders r = BindFields(cloud, convention);
  const bool swap = cloud.is_bigendian != kHostIsBigEndian;
  LidarScan scan;
  scan.frame_id = cloud.frame_id;
  scan.points.reserve(std::size_t{cloud.width} * cloud.height);
  std::vector<int64_t> times_ns;
  times_ns.reserve(scan.points.capacity());
  std::size_t dropped = 0;
  // An empty row (width 0) is not visited: up to 4 G of them would take seconds.
  for (uint32_t row = 0; cloud.width > 0 && row < cloud.height; ++row) {
    const uint8_t* row_start = cloud.data.data() + std::size_t{row} * cloud.row_step;
    for (uint32_t col = 0; col < cloud.width; ++col) {
      const uint8_t* p = row_start + std::size_t{col} * cloud.point_step;
      ScanPoint point;
      point.position_lidar = Eigen::Vector3d(ReadScalar(p, r.x, swap), ReadScalar(p, r.y, swap),
                                             ReadScalar(p, r.z, swap)).cast<float>();
      int64_t t_ns = cloud.stamp_ns;
      const double time = r.time.present() ? ReadScalar(p, r.time, swap) : 0.0;
      if (!point.position_lidar.allFinite() ||
          !ToAbsoluteNs(time, r.time_kind, cloud.stamp_ns, &t_ns)) {
        ++dropped;
        continue;
      }
      if (r.intensity.present()) point.intensity = ReadScalar(p, r.intensity, swap);
      const double ring = r.ring.present() ? ReadScalar(p, r.ring, swap) : 0.0;
      if (std::isfinite(ring)) point.ring = static_cast<uint16_t>(std::clamp(ring, 0.0, 65535.0));
      scan.points.push_back(point);
      times_ns.push_back(t_ns);
    }
  }
  AssignTimes(cloud.stamp_ns, r.time_kind, times_ns, &scan);
  if (dropped_non_finite != nullptr) *dropped_non_finite += dropped;
  return scan;
}

}  // namespace hylo::logs
