// The ROS 2 messages hylo reads and writes, field by field in their definitions' order.

#include "cdr_messages.h"

#include <cstring>
#include <limits>
#include <stdexcept>

#include "cdr_reader.h"
#include "cdr_writer.h"

namespace hylo::logs::detail {
namespace {

constexpr int64_t kNsPerS = 1000000000;

// std_msgs/Header: builtin_interfaces/Time stamp {int32 sec, uint32 nanosec}, string frame_id.
int64_t ReadHeader(CdrReader* in, std::string* frame_id) {
  const int32_t sec = in->Read<int32_t>();
  const uint32_t nanosec = in->Read<uint32_t>();
  std::string frame = in->ReadString();
  if (frame_id != nullptr) *frame_id = std::move(frame);
  return int64_t{sec} * kNsPerS + int64_t{nanosec};
}

void WriteHeader(int64_t t_ns, const std::string& frame_id, CdrWriter* out) {
  // Floor division: nanosec stays in [0, 1e9) for stamps before the epoch too.
  int64_t sec = t_ns / kNsPerS;
  if (t_ns % kNsPerS < 0) --sec;
  if (sec < std::numeric_limits<int32_t>::min() || sec > std::numeric_limits<int32_t>::max()) {
    throw std::invalid_argument("stamp " + std::to_string(t_ns) +
                                " ns does not fit builtin_interfaces/Time (int32 seconds)");
  }
  out->Write(static_cast<int32_t>(sec));
  out->Write(static_cast<uint32_t>(t_ns - sec * kNsPerS));
  out->WriteString(frame_id);
}

Eigen::Vector3d ReadVector3(CdrReader* in) {
  const double x = in->Read<double>();
  const double y = in->Read<double>();
  const double z = in->Read<double>();
  return {x, y, z};
}

void WriteVector3(const Eigen::Vector3d& v, CdrWriter* out) {
  for (int i = 0; i < 3; ++i) out->Write(v[i]);
}

// A PointField: string name (>= 4 bytes), uint32 offset, uint8 datatype, uint32 count.
constexpr std::size_t kMinPointFieldBytes = 13;
// A CustomPoint: uint32 offset_time, float32 x y z, uint8 reflectivity tag line.
constexpr std::size_t kMinCustomPointBytes = 19;

// The Livox PointCloud2 layout (pointcloud2.h): what a CustomMsg becomes.
constexpr uint32_t kLivoxPointStep = 26;

template <typename T>
void Put(uint8_t* at, T value) {
  std::memcpy(at, &value, sizeof(T));
}

}  // namespace

PointCloud2Message DecodeCdrPointCloud2(const uint8_t* data, std::size_t size) {
  CdrReader in(data, size);
  PointCloud2Message cloud;
  cloud.stamp_ns = ReadHeader(&in, &cloud.frame_id);
  cloud.height = in.Read<uint32_t>();
  cloud.width = in.Read<uint32_t>();
  const uint32_t num_fields = in.ReadSequenceLength(kMinPointFieldBytes);
  cloud.fields.resize(num_fields);
  for (PointFieldInfo& f : cloud.fields) {
    f.name = in.ReadString();
    f.offset = in.Read<uint32_t>();
    f.datatype = in.Read<uint8_t>();
    f.count = in.Read<uint32_t>();
  }
  cloud.is_bigendian = in.Read<uint8_t>() != 0;
  cloud.point_step = in.Read<uint32_t>();
  cloud.row_step = in.Read<uint32_t>();
  const uint32_t num_bytes = in.ReadSequenceLength(1);
  const uint8_t* bytes = in.Take(num_bytes);
  cloud.data.assign(bytes, bytes + num_bytes);
  cloud.is_dense = in.Read<uint8_t>() != 0;
  return cloud;
}

ImuSample DecodeCdrImu(const uint8_t* data, std::size_t size) {
  CdrReader in(data, size);
  ImuSample imu;
  imu.t_ns = ReadHeader(&in, nullptr);
  in.Skip(4 + 9, sizeof(double));  // orientation (x y z w), its covariance
  imu.gyro_imu = ReadVector3(&in);
  in.Skip(9, sizeof(double));
  imu.accel_imu = ReadVector3(&in);
  in.Skip(9, sizeof(double));
  return imu;
}

PointCloud2Message DecodeCdrLivoxCustom(const uint8_t* data, std::size_t size) {
  CdrReader in(data, size);
  PointCloud2Message cloud;
  cloud.stamp_ns = ReadHeader(&in, &cloud.frame_id);
  const uint64_t timebase_ns = in.Read<uint64_t>();
  in.Read<uint32_t>();  // point_num: the sequence's own length is what the bytes hold
  in.Skip(1 + 3, 1);    // lidar_id, rsvd[3]
  const uint32_t n = in.ReadSequenceLength(kMinCustomPointBytes);
  cloud.height = 1;
  cloud.width = n;
  cloud.fields = {{"x", kFloat32, 0, 1},          {"y", kFloat32, 4, 1},  {"z", kFloat32, 8, 1},
                  {"intensity", kFloat32, 12, 1}, {"tag", kUint8, 16, 1}, {"line", kUint8, 17, 1},
                  {"timestamp", kFloat64, 18, 1}};
  cloud.point_step = kLivoxPointStep;
  cloud.row_step = n * kLivoxPointStep;
  cloud.data.resize(std::size_t{cloud.row_step});
  cloud.is_dense = true;
  for (uint32_t i = 0; i < n; ++i) {
    uint8_t* p = cloud.data.data() + std::size_t{i} * kLivoxPointStep;
    const uint32_t offset_time_ns = in.Read<uint32_t>();
    Put(p + 0, in.Read<float>());
    Put(p + 4, in.Read<float>());
    Put(p + 8, in.Read<float>());
    Put(p + 12, static_cast<float>(in.Read<uint8_t>()));  // reflectivity
    p[16] = in.Read<uint8_t>();                           // tag
    p[17] = in.Read<uint8_t>();                           // line
    Put(p + 18, static_cast<double>(timebase_ns + offset_time_ns));
  }
  return cloud;
}

PointCloud2Message DecodeCdrCloud(const std::string& type, const uint8_t* data, std::size_t size) {
  return type == kLivoxCustomType ? DecodeCdrLivoxCustom(data, size)
                                  : DecodeCdrPointCloud2(data, size);
}

std::vector<uint8_t> EncodeCdrPointCloud2(const PointCloud2Message& cloud) {
  CdrWriter out(cloud.data.size() + 64 * (cloud.fields.size() + 2));
  WriteHeader(cloud.stamp_ns, cloud.frame_id, &out);
  out.Write(cloud.height);
  out.Write(cloud.width);
  out.WriteSequenceLength(cloud.fields.size());
  for (const PointFieldInfo& f : cloud.fields) {
    out.WriteString(f.name);
    out.Write(f.offset);
    out.Write(f.datatype);
    out.Write(f.count);
  }
  out.Write(static_cast<uint8_t>(cloud.is_bigendian));
  out.Write(cloud.point_step);
  out.Write(cloud.row_step);
  out.WriteSequenceLength(cloud.data.size());
  out.WriteBytes(cloud.data.data(), cloud.data.size());
  out.Write(static_cast<uint8_t>(cloud.is_dense));
  return out.Take();
}

std::vector<uint8_t> EncodeCdrImu(const ImuSample& imu, const std::string& frame_id) {
  CdrWriter out;
  WriteHeader(imu.t_ns, frame_id, &out);
  for (const double q : {0.0, 0.0, 0.0, 1.0}) out.Write(q);
  for (int i = 0; i < 9; ++i) out.Write(i == 0 ? -1.0 : 0.0);  // orientation unknown
  WriteVector3(imu.gyro_imu, &out);
  for (int i = 0; i < 9; ++i) out.Write(0.0);
  WriteVector3(imu.accel_imu, &out);
  for (int i = 0; i < 9; ++i) out.Write(0.0);
  return out.Take();
}

std::vector<uint8_t> EncodeCdrLivoxCustom(int64_t stamp_ns, const std::string& frame_id,
                                          uint64_t timebase_ns,
                                          const std::vector<LivoxCustomPoint>& points) {
  CdrWriter out(points.size() * 20 + 64);
  WriteHeader(stamp_ns, frame_id, &out);
  out.Write(timebase_ns);
  out.Write(static_cast<uint32_t>(points.size()));
  for (int i = 0; i < 4; ++i) out.Write(uint8_t{0});  // lidar_id, rsvd[3]
  out.WriteSequenceLength(points.size());
  for (const LivoxCustomPoint& p : points) {
    out.Write(p.offset_time_ns);
    out.Write(p.x);
    out.Write(p.y);
    out.Write(p.z);
    out.Write(p.reflectivity);
    out.Write(p.tag);
    out.Write(p.line);
  }
  return out.Take();
}

namespace {

const char kSeparator[] =
    "================================================================================\n";

std::string Dependency(const char* name, const char* text) {
  return std::string(kSeparator) + "MSG: " + name + "\n" + text;
}

const char kHeader[] = "builtin_interfaces/Time stamp\nstring frame_id\n";
const char kTime[] = "int32 sec\nuint32 nanosec\n";

}  // namespace

std::string Ros2MessageDefinition(const std::string& type) {
  if (type == kRos2CloudType) {
    return std::string(
               "std_msgs/Header header\nuint32 height\nuint32 width\nPointField[] fields\n"
               "bool is_bigendian\nuint32 point_step\nuint32 row_step\nuint8[] data\n"
               "bool is_dense\n") +
           Dependency("std_msgs/Header", kHeader) + Dependency("builtin_interfaces/Time", kTime) +
           Dependency("sensor_msgs/PointField",
                      "uint8 INT8=1\nuint8 UINT8=2\nuint8 INT16=3\nuint8 UINT16=4\n"
                      "uint8 INT32=5\nuint8 UINT32=6\nuint8 FLOAT32=7\nuint8 FLOAT64=8\n"
                      "string name\nuint32 offset\nuint8 datatype\nuint32 count\n");
  }
  if (type == kRos2ImuType) {
    return std::string(
               "std_msgs/Header header\ngeometry_msgs/Quaternion orientation\n"
               "float64[9] orientation_covariance\ngeometry_msgs/Vector3 angular_velocity\n"
               "float64[9] angular_velocity_covariance\n"
               "geometry_msgs/Vector3 linear_acceleration\n"
               "float64[9] linear_acceleration_covariance\n") +
           Dependency("std_msgs/Header", kHeader) + Dependency("builtin_interfaces/Time", kTime) +
           Dependency("geometry_msgs/Quaternion",
                      "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n") +
           Dependency("geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n");
  }
  if (type == kLivoxCustomType) {
    return std::string(
               "std_msgs/Header header\nuint64 timebase\nuint32 point_num\nuint8 lidar_id\n"
               "uint8[3] rsvd\nCustomPoint[] points\n") +
           Dependency("std_msgs/Header", kHeader) + Dependency("builtin_interfaces/Time", kTime) +
           Dependency("livox_ros_driver2/CustomPoint",
                      "uint32 offset_time\nfloat32 x\nfloat32 y\nfloat32 z\nuint8 reflectivity\n"
                      "uint8 tag\nuint8 line\n");
  }
  return "";
}

}  // namespace hylo::logs::detail
