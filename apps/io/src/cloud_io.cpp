// Extension dispatch and the KITTI .bin format (float32 x y z intensity, no header).

#include "hylo/io/cloud_io.h"

#include <filesystem>

#include "cloud_fields.h"

namespace hylo::io {
namespace {

constexpr std::size_t kKittiRecordBytes = 4 * sizeof(float);

std::string Extension(const std::string& path) {
  return internal::ToLower(std::filesystem::path(path).extension().string());
}

[[noreturn]] void UnknownExtension(const std::string& path) {
  internal::ThrowFileError(path, "unknown point cloud extension '" + Extension(path) +
                                     "' (expected .pcd, .ply or .bin)");
}

}  // namespace

CloudFile ReadCloud(const std::string& path) {
  const std::string ext = Extension(path);
  if (ext == ".pcd") return ReadPcd(path);
  if (ext == ".ply") return ReadPly(path);
  if (ext == ".bin") return ReadKittiBin(path);
  UnknownExtension(path);
}

CloudFileInfo ReadCloudInfo(const std::string& path) {
  const std::string ext = Extension(path);
  if (ext == ".pcd") return ReadPcdInfo(path);
  if (ext == ".ply") return ReadPlyInfo(path);
  if (ext != ".bin") UnknownExtension(path);
  std::ifstream in = internal::OpenForReading(path);
  in.seekg(0, std::ios::end);
  CloudFileInfo info;
  info.format = "kitti_bin";
  info.encoding = "binary";
  info.fields = {"x", "y", "z", "intensity"};
  info.points = static_cast<std::size_t>(in.tellg()) / kKittiRecordBytes;
  return info;
}

void WriteCloud(const std::string& path, const CloudFile& cloud, CloudEncoding encoding) {
  const std::string ext = Extension(path);
  if (ext == ".pcd") return WritePcd(path, cloud, encoding);
  if (ext == ".ply") return WritePly(path, cloud, encoding);
  if (ext != ".bin") UnknownExtension(path);
  if (encoding != CloudEncoding::kBinary) {
    internal::ThrowFileError(path, "cannot write: KITTI .bin is binary only");
  }
  WriteKittiBin(path, cloud);
}

CloudFile ReadKittiBin(const std::string& path) {
  std::ifstream in = internal::OpenForReading(path);
  const std::vector<uint8_t> bytes = internal::ReadRest(&in);
  if (bytes.size() % kKittiRecordBytes != 0) {
    internal::ThrowFileError(path, "truncated: " + std::to_string(bytes.size()) +
                                       " bytes is not a whole number of 16-byte x y z i records");
  }
  const bool present[internal::kNumSlots] = {true, true, true, true};
  const std::size_t n = bytes.size() / kKittiRecordBytes;
  internal::CloudBuilder builder(path, present, n);
  const internal::ScalarType f32{internal::ScalarKind::kFloat, 4};
  double record[internal::kNumSlots] = {};
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 4; ++k) {
      record[k] = internal::DecodeScalar(bytes.data() + i * kKittiRecordBytes + 4 * k, f32, false);
    }
    builder.Add(record);
  }
  return builder.Finish();
}

void WriteKittiBin(const std::string& path, const CloudFile& cloud) {
  internal::CheckAttributeSizes(path, cloud);
  // Refuse rather than silently drop what the format cannot hold.
  if (!cloud.normals.empty() || !cloud.labels.empty()) {
    internal::ThrowFileError(path, "cannot write: KITTI .bin holds x y z intensity only, the "
                                   "cloud has normals or labels (use .pcd or .ply)");
  }
  std::vector<uint8_t> body;
  body.reserve(cloud.positions.size() * kKittiRecordBytes);
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      internal::AppendBytes(&body, static_cast<float>(cloud.positions[i][k]));
    }
    internal::AppendBytes(&body, cloud.intensity.empty() ? 0.f : cloud.intensity[i]);
  }
  internal::WriteFileOrThrow(path, "", body);
}

}  // namespace hylo::io
