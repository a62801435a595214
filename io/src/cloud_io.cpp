// Extension dispatch (LAZ refused here) and the KITTI .bin format (float32 x y z intensity, no header).

#include "hylo/io/cloud_io.h"

#include <algorithm>
#include <filesystem>
#include <limits>

#include "cloud_fields.h"
#include "cloud_streams.h"
#include "hylo/io/cloud_stream.h"
#include "las_format.h"

namespace hylo::io {
namespace {

constexpr std::size_t kKittiRecordBytes = 4 * sizeof(float);

std::string Extension(const std::string& path) {
  return ToLower(std::filesystem::path(path).extension().string());
}

[[noreturn]] void UnknownExtension(const std::string& path) {
  if (Extension(path) == ".laz") ThrowFileError(path, internal::LazRefusal(path));
  ThrowFileError(path, "unknown point cloud extension '" + Extension(path) +
                           "' (expected .pcd, .ply, .bin or .las)");
}

}  // namespace

CloudFile ReadCloud(const std::string& path) {
  const std::string ext = Extension(path);
  if (ext == ".pcd") return ReadPcd(path);
  if (ext == ".ply") return ReadPly(path);
  if (ext == ".bin") return ReadKittiBin(path);
  if (ext == ".las") return ReadLas(path);
  UnknownExtension(path);
}

CloudFileInfo ReadCloudInfo(const std::string& path) {
  const std::string ext = Extension(path);
  if (ext == ".pcd") return ReadPcdInfo(path);
  if (ext == ".ply") return ReadPlyInfo(path);
  if (ext == ".las") return ReadLasInfo(path);
  if (ext != ".bin") UnknownExtension(path);
  return internal::OpenKittiStream(path)->info();
}

void WriteCloud(const std::string& path, const CloudFile& cloud, CloudEncoding encoding) {
  const std::string ext = Extension(path);
  if (ext == ".pcd") return WritePcd(path, cloud, encoding);
  if (ext == ".ply") return WritePly(path, cloud, encoding);
  if (ext == ".laz") {
    ThrowFileError(path, "cannot write LAZ (compressed LAS): write .las and compress it with "
                         "'laszip' or 'pdal translate'");
  }
  if (ext != ".bin" && ext != ".las") UnknownExtension(path);
  if (encoding != CloudEncoding::kBinary) {
    ThrowFileError(path, std::string("cannot write: ") + (ext == ".las" ? "LAS" : "KITTI .bin") +
                             " is binary only");
  }
  if (ext == ".las") return WriteLas(path, cloud);
  WriteKittiBin(path, cloud);
}

namespace {

// KITTI .bin: 16-byte records (float32 x y z intensity) from the first byte on.
class KittiStream final : public CloudStream {
 public:
  explicit KittiStream(const std::string& path)
      : CloudStream(path), in_(internal::OpenForReading(path)) {
    const std::size_t bytes = internal::BytesLeft(&in_);
    if (bytes % kKittiRecordBytes != 0) {
      ThrowFileError(path, "truncated: " + std::to_string(bytes) +
                                         " bytes is not a whole number of 16-byte x y z i records");
    }
    info_.format = "kitti_bin";
    info_.encoding = "binary";
    info_.fields = {"x", "y", "z", "intensity"};
    info_.points = bytes / kKittiRecordBytes;
  }

  bool Next(std::size_t max_points, CloudFile* chunk) override {
    *chunk = CloudFile();
    const std::size_t n = std::min(max_points, info_.points - records_read_);
    if (n == 0) return false;
    buffer_.resize(n * kKittiRecordBytes);
    in_.read(reinterpret_cast<char*>(buffer_.data()), static_cast<std::streamsize>(buffer_.size()));
    if (static_cast<std::size_t>(in_.gcount()) != buffer_.size()) {
      ThrowFileError(path_, "truncated: the file shrank while it was read");
    }
    const bool present[internal::kNumSlots] = {true, true, true, true};
    internal::CloudBuilder builder(path_, present, n);
    const internal::ScalarType f32{internal::ScalarKind::kFloat, 4};
    double record[internal::kNumSlots] = {};
    for (std::size_t i = 0; i < n; ++i) {
      for (int k = 0; k < 4; ++k) {
        record[k] =
            internal::DecodeScalar(buffer_.data() + i * kKittiRecordBytes + 4 * k, f32, false);
      }
      builder.Add(record);
    }
    *chunk = builder.Finish();
    records_read_ += n;
    return true;
  }

 private:
  std::ifstream in_;
  std::vector<uint8_t> buffer_;
};

}  // namespace

std::unique_ptr<CloudStream> internal::OpenKittiStream(const std::string& path) {
  return std::make_unique<KittiStream>(path);
}

std::unique_ptr<CloudStream> CloudStream::Open(const std::string& path) {
  const std::string ext = Extension(path);
  if (ext == ".pcd") return internal::OpenPcdStream(path, /*whole=*/false);
  if (ext == ".ply") return internal::OpenPlyStream(path);
  if (ext == ".bin") return internal::OpenKittiStream(path);
  if (ext == ".las") return internal::OpenLasStream(path);
  UnknownExtension(path);
}

CloudFile ReadAll(CloudStream* stream) {
  CloudFile all;
  CloudFile chunk;
  for (bool first = true; stream->Next(std::numeric_limits<std::size_t>::max(), &chunk);
       first = false) {
    if (first) {
      all = std::move(chunk);
      continue;
    }
    all.positions.insert(all.positions.end(), chunk.positions.begin(), chunk.positions.end());
    all.intensity.insert(all.intensity.end(), chunk.intensity.begin(), chunk.intensity.end());
    all.normals.insert(all.normals.end(), chunk.normals.begin(), chunk.normals.end());
    all.labels.insert(all.labels.end(), chunk.labels.begin(), chunk.labels.end());
    all.dropped_non_finite += chunk.dropped_non_finite;
  }
  return all;
}

CloudFile ReadKittiBin(const std::string& path) {
  return ReadAll(internal::OpenKittiStream(path).get());
}

void WriteKittiBin(const std::string& path, const CloudFile& cloud) {
  internal::CheckAttributeSizes(path, cloud);
  // Refuse rather than silently drop what the format cannot hold.
  if (!cloud.normals.empty() || !cloud.labels.empty()) {
    ThrowFileError(path,
                             "cannot write: KITTI .bin holds x y z intensity only, the "
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
