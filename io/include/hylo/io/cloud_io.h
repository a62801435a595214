#pragma once
// Point cloud files (PCD v0.7, PLY, KITTI .bin, LAS 1.0-1.4) read and written without PCL.
// Positions are double so that georeferenced (UTM) coordinates survive a round trip;
// the core shifts them near zero itself (common/local_origin.h).
//
// LAS (ASPRS LAS 1.0-1.4, point data record formats 0-10): positions are the records' integers
// times the header's scale plus its offset, in double; `intensity` is the LAS intensity and
// `labels` the ASPRS classification (formats 0-5: its 5 class bits; 2 = ground, 6 = building,
// ...), which is what survey software and the ground filter's users mean by a point's class.
// Normals are read from extra bytes described as NormalX/Y/Z (or normal_x, nx, ...). Colour,
// GPS time, returns and other extra bytes are skipped; withheld points are kept. LAZ (compressed
// LAS, a .laz file or a LAS header with the compression bit) is refused with how to convert it.
// WriteCloud writes LAS 1.4 point format 6 on a 0.1 mm grid (see WriteLas).

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
  std::vector<int32_t> labels;             ///< `label` field (class or segment id); LAS:
                                           ///< the classification
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
  std::string format;               ///< "pcd", "ply", "kitti_bin" or "las"
  std::string encoding;             ///< as named in the header ("binary_compressed", ...;
                                    ///< LAS: "LAS 1.4 point format 6")
  std::vector<std::string> fields;  ///< field names in file order (PLY: the vertex element)
  std::size_t points = 0;           ///< points announced (organized PCD: width * height)
};

/// Reads a cloud, choosing the format from the extension (.pcd, .ply, .bin = KITTI float32
/// x y z intensity, .las; case-insensitive). Points with a non-finite coordinate are dropped and
/// counted. Throws std::runtime_error naming the file and the reason: missing file, unknown
/// extension, malformed header, missing x/y/z, fewer data bytes than the header promises
/// (LAS: every count, length and offset of the header, VLRs and EVLRs is checked against the
/// file's size first), LAZ.
CloudFile ReadCloud(const std::string& path);

/// Reads only the header (cheap on large files). Same errors as ReadCloud for the header.
CloudFileInfo ReadCloudInfo(const std::string& path);

/// Writes a cloud, format from the extension. Positions are stored as float32 when that is
/// exact or every coordinate is within +-1e4 m (error <= 0.5 mm, and PCL's float point types
/// load the file); otherwise as float64 (UTM coordinates keep their millimetres). LAS: see
/// WriteLas (binary only).
/// Throws std::runtime_error naming the file when it cannot be written, when attribute sizes
/// disagree with the positions, or when the format cannot hold the request (PLY has no
/// compressed encoding; KITTI .bin is binary float32 x y z intensity only; LAS see WriteLas;
/// LAZ is not written).
void WriteCloud(const std::string& path, const CloudFile& cloud,
                CloudEncoding encoding = CloudEncoding::kBinary);

/// The positions a LAS file WriteCloud writes at `path` from `positions` (finite ones) reads
/// back as: quantized to the grid the writer picks for them. Throws as WriteLas when no grid
/// can hold them.
std::vector<Eigen::Vector3d> LasQuantizedPositions(const std::string& path,
                                                   const std::vector<Eigen::Vector3d>& positions);

/// Format-specific entry points (ReadCloud/WriteCloud dispatch to these).
CloudFile ReadPcd(const std::string& path);
CloudFileInfo ReadPcdInfo(const std::string& path);
void WritePcd(const std::string& path, const CloudFile& cloud, CloudEncoding encoding);
CloudFile ReadPly(const std::string& path);
CloudFileInfo ReadPlyInfo(const std::string& path);
void WritePly(const std::string& path, const CloudFile& cloud, CloudEncoding encoding);
CloudFile ReadKittiBin(const std::string& path);
void WriteKittiBin(const std::string& path, const CloudFile& cloud);
CloudFile ReadLas(const std::string& path);
CloudFileInfo ReadLasInfo(const std::string& path);

/// LAS 1.4, point data record format 6 (normals as three float32 extra bytes NormalX/Y/Z).
/// Quantization: each axis is stored as round((coordinate - offset) / scale) in int32 with a
/// scale of 0.1 mm (1 mm or 1 cm only for a cloud spanning more than 214 km along an axis) and
/// an offset on a 1 km grid near the smallest coordinate, so UTM coordinates keep 0.1 mm. A
/// cloud not on that grid moves by at most half a step (0.05 mm) per axis; reading the file
/// gives the quantized positions exactly, and writing those again gives the same bytes.
/// Intensity is rounded to an integer; labels are the classification. Refuses (throws naming
/// the file and the point) a non-finite coordinate, an intensity outside 0-65535 or a label
/// outside 0-255, rather than clipping them.
void WriteLas(const std::string& path, const CloudFile& cloud);

}  // namespace hylo::io
