#pragma once
// Point cloud files (PCD v0.7, PLY, KITTI .bin) read and written without PCL.
// Positions are double so that georeferenced (UTM) coordinates survive a round trip;
// the core shifts them near zero itself (mapping/local_origin.h).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hylo::io {

/// A cloud as stored in a file. Attribute vectors are empty when the file has no such
/// field, else exactly as long as `positions`.
struct CloudFile {
  std::vector<Eigen::Vector3d> positions;  ///< file frame, m
  std::vector<float> intensity;            ///< `intensity` field, file units
  std::vector<Eigen::Vector3f> normals;    ///< `normal_x/y/z` (PCD) or `nx/ny/nz` (PLY)
  std::vector<int32_t> labels;             ///< `label` field (class or segment id)
  std::size_t dropped_non_finite = 0;      ///< points with a NaN/inf coordinate, not stored
};

/// How a file body is stored.
enum class CloudEncoding {
  kAscii,             ///< text (PCD, PLY)
  kBinary,            ///< little-endian binary (PCD, PLY, KITTI .bin)
  kBinaryCompressed,  ///< PCD only: field-major data, LZF-compressed
};

/// What a file header announces, without reading the points.
struct CloudFileInfo {
  std::string format;               ///< "pcd", "ply" or "kitti_bin"
  std::string encoding;             ///< as named in the header ("binary_compressed", ...)
  std::vector<std::string> fields;  ///< field names in file order (PLY: the vertex element)
  std::size_t points = 0;           ///< points announced (organized PCD: width * height)
};

/// Reads a cloud, choosing the format from the extension (.pcd, .ply, .bin = KITTI float32
/// x y z intensity; case-insensitive). Points with a non-finite coordinate are dropped and
/// counted. Throws std::runtime_error naming the file and the reason: missing file, unknown
/// extension, malformed header, missing x/y/z, fewer data bytes than the header promises.
CloudFile ReadCloud(const std::string& path);

/// Reads only the header (cheap on large files). Same errors as ReadCloud for the header.
CloudFileInfo ReadCloudInfo(const std::string& path);

/// Writes a cloud, format from the extension. Positions are stored as float32 when that is
/// exact or every coordinate is within +-1e4 m (error <= 0.5 mm, and PCL's float point types
/// load the file); otherwise as float64 (UTM coordinates keep their millimetres).
/// Throws std::runtime_error naming the file when it cannot be written, when attribute sizes
/// disagree with the positions, or when the format cannot hold the request (PLY has no
/// compressed encoding; KITTI .bin is binary float32 x y z intensity only).
void WriteCloud(const std::string& path, const CloudFile& cloud,
                CloudEncoding encoding = CloudEncoding::kBinary);

/// Format-specific entry points (ReadCloud/WriteCloud dispatch to these).
CloudFile ReadPcd(const std::string& path);
CloudFileInfo ReadPcdInfo(const std::string& path);
void WritePcd(const std::string& path, const CloudFile& cloud, CloudEncoding encoding);
CloudFile ReadPly(const std::string& path);
CloudFileInfo ReadPlyInfo(const std::string& path);
void WritePly(const std::string& path, const CloudFile& cloud, CloudEncoding encoding);
CloudFile ReadKittiBin(const std::string& path);
void WriteKittiBin(const std::string& path, const CloudFile& cloud);

}  // namespace hylo::io
