// LAS writer: LAS 1.4, point data record format 6 (30 bytes: x y z int32, intensity, returns,
// classification, scan angle, GPS time), because it is the 1.4 base format: classification has
// all 8 bits (formats 0-5 keep 5), and point counts are 64-bit. Compatibility with readers that
// stop at LAS 1.2 (format 1) was weighed against that: every maintained reader (PDAL, LAStools,
// laspy, CloudCompare, QGIS) reads 1.4, and a 1.2 file could not hold classes above 31.
//
// Positions go on a grid of 0.1 mm (ChooseLasGrid); intensity is rounded to the format's integer
// (0-65535) and labels become the classification (0-255): a cloud outside those ranges is
// refused, never clipped. Normals, when the cloud has them, are three float32 extra bytes
// (NormalX/Y/Z, described by an Extra Bytes VLR, the names PDAL gives them). Returns are 1 of 1,
// GPS time 0; the creation date is left 0 so that the same cloud always gives the same bytes.

#include <cmath>
#include <cstring>
#include <limits>

#include "cloud_fields.h"
#include "hylo/io/cloud_io.h"
#include "las_format.h"

namespace hylo::io {
namespace {

using internal::AppendBytes;

constexpr int kFormat = 6;
constexpr std::size_t kRecordBytes = 30;
constexpr std::size_t kNormalBytes = 3 * sizeof(float);
constexpr uint16_t kGlobalEncodingWkt = 1 << 4;  // formats 6-10 must declare a WKT CRS
constexpr double kOffsetGranularityM = 1000.0;
constexpr double kScales[] = {1e-4, 1e-3, 1e-2};

void AppendText(std::vector<uint8_t>* out, const std::string& text, std::size_t size) {
  const std::size_t at = out->size();
  out->resize(at + size, 0);  // unused characters must be zero
  std::memcpy(out->data() + at, text.data(), std::min(size, text.size()));
}

void AppendZeros(std::vector<uint8_t>* out, std::size_t size) {
  out->resize(out->size() + size, 0);
}

// The Extra Bytes VLR describing NormalX/Y/Z as float32 (data type 9).
std::vector<uint8_t> NormalsVlr() {
  std::vector<uint8_t> v;
  AppendBytes<uint16_t>(&v, 0);
  AppendText(&v, "LASF_Spec", 16);
  AppendBytes<uint16_t>(&v, 4);
  AppendBytes<uint16_t>(&v, 3 * internal::kLasExtraBytesDescriptorBytes);
  AppendText(&v, "Extra Bytes Record", 32);
  for (const char axis : {'X', 'Y', 'Z'}) {
    AppendZeros(&v, 2);
    v.push_back(9);  // float
    v.push_back(0);  // no options: no scale, offset, min, max or no-data value
    AppendText(&v, std::string("Normal") + axis, 32);
    AppendZeros(&v, 4 + 24 * 5);  // unused, no_data, min, max, scale, offset (+ deprecated)
    AppendText(&v, std::string("surface normal, ") + static_cast<char>(axis + 32), 32);
  }
  return v;
}

// Refuses what LAS cannot hold rather than clipping it.
void CheckWritable(const std::string& path, const CloudFile& cloud) {
  internal::CheckAttributeSizes(path, cloud);
  const auto refuse = [&](std::size_t i, const std::string& what) {
    ThrowFileError(path, "cannot write: point " + std::to_string(i) + " " + what +
                             " (use .pcd or .ply to keep it)");
  };
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    if (!cloud.positions[i].allFinite()) refuse(i, "has a non-finite coordinate");
    if (!cloud.intensity.empty() &&
        !(cloud.intensity[i] > -0.5f && cloud.intensity[i] < 65535.5f)) {
      refuse(i, "has intensity " + internal::FormatShortest(cloud.intensity[i]) +
                    ", LAS holds 0-65535");
    }
    if (!cloud.labels.empty() && (cloud.labels[i] < 0 || cloud.labels[i] > 255)) {
      refuse(i, "has label " + std::to_string(cloud.labels[i]) + ", a LAS classification is 0-255");
    }
  }
}

std::vector<uint8_t> Header(std::size_t points, std::size_t vlr_bytes, const internal::LasGrid& g,
                            const Eigen::Vector3d& min, const Eigen::Vector3d& max, bool normals) {
  std::vector<uint8_t> h;
  AppendText(&h, "LASF", 4);
  AppendBytes<uint16_t>(&h, 0);  // file source ID: none assigned
  AppendBytes<uint16_t>(&h, kGlobalEncodingWkt);
  AppendZeros(&h, 16);  // project ID
  h.push_back(1);
  h.push_back(4);
  AppendText(&h, "OTHER", 32);  // system identifier: not a sensor, merge or extraction
  AppendText(&h, "hylo", 32);
  AppendBytes<uint16_t>(&h, 0);  // creation day and year: 0 keeps the bytes reproducible
  AppendBytes<uint16_t>(&h, 0);
  AppendBytes<uint16_t>(&h, internal::kLasHeaderBytes14);
  AppendBytes<uint32_t>(&h, static_cast<uint32_t>(internal::kLasHeaderBytes14 + vlr_bytes));
  AppendBytes<uint32_t>(&h, normals ? 1 : 0);
  h.push_back(kFormat);
  AppendBytes<uint16_t>(&h, static_cast<uint16_t>(kRecordBytes + (normals ? kNormalBytes : 0)));
  AppendZeros(&h, 4 + 20);  // legacy counts: 0 for formats 6-10
  for (int k = 0; k < 3; ++k) AppendBytes(&h, g.scale[k]);
  for (int k = 0; k < 3; ++k) AppendBytes(&h, g.offset[k]);
  for (int k = 0; k < 3; ++k) {
    AppendBytes(&h, max[k]);
    AppendBytes(&h, min[k]);
  }
  AppendZeros(&h, 8 + 8 + 4);  // no waveform data, no EVLRs
  AppendBytes<uint64_t>(&h, points);
  AppendBytes<uint64_t>(&h, points);  // every point is return 1 of 1
  AppendZeros(&h, 14 * 8);
  return h;
}

}  // namespace

internal::LasGrid internal::ChooseLasGrid(const std::string& path,
                                          const std::vector<Eigen::Vector3d>& positions) {
  LasGrid grid;
  if (positions.empty()) return grid;
  Eigen::Vector3d lo = positions.front(), hi = positions.front();
  for (const Eigen::Vector3d& p : positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  constexpr double kMaxRecord = std::numeric_limits<int32_t>::max();
  for (int k = 0; k < 3; ++k) {
    bool fits = false;
    for (const double s : kScales) {
      // The offset is on a 1 km grid at most s/2 above the smallest coordinate, so records start
      // at 0 and read-back positions (at most s/2 away) fall on the same offset.
      grid.scale[k] = s;
      grid.offset[k] = kOffsetGranularityM * std::floor((lo[k] + s / 2) / kOffsetGranularityM);
      if (std::floor((hi[k] - grid.offset[k]) / s + 0.5) <= kMaxRecord) {
        fits = true;
        break;
      }
    }
    if (!fits) {
      ThrowFileError(path, std::string("cannot write: the cloud spans ") +
                               FormatShortest(hi[k] - lo[k]) + " m along " +
                               static_cast<char>('x' + k) +
                               ", more than LAS's 32-bit records hold at 1 cm");
    }
  }
  return grid;
}

Eigen::Vector3i internal::LasQuantize(const Eigen::Vector3d& p, const LasGrid& grid) {
  Eigen::Vector3i record;
  for (int k = 0; k < 3; ++k) {
    record[k] = static_cast<int32_t>(std::floor((p[k] - grid.offset[k]) / grid.scale[k] + 0.5));
  }
  return record;
}

std::vector<Eigen::Vector3d> LasQuantizedPositions(
    const std::string& path, const std::vector<Eigen::Vector3d>& positions) {
  const internal::LasGrid grid = internal::ChooseLasGrid(path, positions);
  std::vector<Eigen::Vector3d> out;
  out.reserve(positions.size());
  for (const Eigen::Vector3d& p : positions) {
    const Eigen::Vector3i r = internal::LasQuantize(p, grid);
    out.emplace_back(internal::LasCoordinate(r.x(), grid.scale.x(), grid.offset.x()),
                     internal::LasCoordinate(r.y(), grid.scale.y(), grid.offset.y()),
                     internal::LasCoordinate(r.z(), grid.scale.z(), grid.offset.z()));
  }
  return out;
}

void WriteLas(const std::string& path, const CloudFile& cloud) {
  CheckWritable(path, cloud);
  const internal::LasGrid grid = internal::ChooseLasGrid(path, cloud.positions);
  const bool normals = !cloud.normals.empty();
  const std::size_t n = cloud.positions.size();
  std::vector<uint8_t> body;
  body.reserve(n * (kRecordBytes + (normals ? kNormalBytes : 0)));
  Eigen::Vector3i lo = Eigen::Vector3i::Constant(std::numeric_limits<int32_t>::max());
  Eigen::Vector3i hi = Eigen::Vector3i::Constant(std::numeric_limits<int32_t>::min());
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3i r = internal::LasQuantize(cloud.positions[i], grid);
    lo = lo.cwiseMin(r);
    hi = hi.cwiseMax(r);
    for (int k = 0; k < 3; ++k) AppendBytes<int32_t>(&body, r[k]);
    const float intensity = cloud.intensity.empty() ? 0.f : std::round(cloud.intensity[i]);
    AppendBytes<uint16_t>(&body, static_cast<uint16_t>(intensity));
    body.push_back(0x11);  // return 1 of 1
    body.push_back(0);     // classification flags, scanner channel, scan direction, edge
    body.push_back(cloud.labels.empty() ? 0 : static_cast<uint8_t>(cloud.labels[i]));
    body.push_back(0);              // user data
    AppendZeros(&body, 2 + 2 + 8);  // scan angle, point source ID, GPS time
    if (normals) {
      for (int k = 0; k < 3; ++k) AppendBytes(&body, cloud.normals[i][k]);
    }
  }
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3 && n > 0; ++k) {
    min[k] = internal::LasCoordinate(lo[k], grid.scale[k], grid.offset[k]);
    max[k] = internal::LasCoordinate(hi[k], grid.scale[k], grid.offset[k]);
  }
  const std::vector<uint8_t> vlr = normals ? NormalsVlr() : std::vector<uint8_t>();
  std::vector<uint8_t> head = Header(n, vlr.size(), grid, min, max, normals);
  head.insert(head.end(), vlr.begin(), vlr.end());
  internal::WriteFileOrThrow(path, std::string(head.begin(), head.end()), body);
}

}  // namespace hylo::io
