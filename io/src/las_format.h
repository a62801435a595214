#pragma once
// Internal to hylo::io: the ASPRS LAS format (1.0-1.4, point data record formats 0-10), shared by
// the reader (las_header.cpp, las_read.cpp), the writer (las_write.cpp) and the map tiler, which
// needs the positions a LAS tile will read back as.
//
// Byte offsets and sizes are the specification's (LAS 1.4 R15, "Public Header Block", "Point
// Data Records", "Extra Bytes"). Every file is little-endian.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace hylo::io::internal {

/// Public header sizes: 1.0-1.2, 1.3 (+ waveform start), 1.4 (+ EVLRs, 64-bit counts).
constexpr std::size_t kLasHeaderBytes12 = 227;
constexpr std::size_t kLasHeaderBytes13 = 235;
constexpr std::size_t kLasHeaderBytes14 = 375;
constexpr std::size_t kLasVlrHeaderBytes = 54;
constexpr std::size_t kLasEvlrHeaderBytes = 60;
constexpr std::size_t kLasExtraBytesDescriptorBytes = 192;
constexpr int kLasMaxPointFormat = 10;

/// Bytes of the fields point data record format `format` (0-10) defines; a record may be
/// longer (user "extra bytes").
std::size_t LasStandardRecordBytes(int format);

/// What one extra-bytes descriptor says about a value the reader uses (a normal component).
struct LasExtraScalar {
  std::size_t offset = 0;  ///< bytes from the start of the record
  int type = 0;            ///< the descriptor's data type (9 float, 10 double)
  double scale = 1.0;      ///< applied when the descriptor's option bit says so
  double add = 0.0;        ///< its offset, likewise
};

/// The header as far as a reader needs it, every field checked against the file's size.
struct LasHeader {
  int version_major = 1;
  int version_minor = 2;
  std::size_t header_bytes = kLasHeaderBytes12;
  std::size_t point_data_offset = 0;  ///< byte of the first point record
  int point_format = 0;               ///< 0-10
  std::size_t record_bytes = 0;       ///< bytes per point record (standard + extra)
  uint64_t points = 0;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  bool has_normals = false;                 ///< extra bytes named as normals, all three
  std::array<LasExtraScalar, 3> normals{};  ///< valid when has_normals
  std::vector<std::string> extra_names;     ///< the extra bytes' descriptor names, in order
};

/// Reads and checks the header, the VLRs (bounds only, except the extra-bytes descriptors) and
/// the EVLRs (bounds only) of the LAS file open in `in`; `in` is left at the first point record.
/// Throws std::runtime_error naming `path` and what is wrong: no LASF signature, a version other
/// than 1.0-1.4, LAZ compression, an unknown point format, a record shorter than its format,
/// a zero or non-finite scale, a non-finite offset, point data, VLRs or EVLRs beyond the file
/// or overlapping each other.
LasHeader ReadLasHeader(const std::string& path, std::ifstream* in);

/// The one-line refusal of a compressed (LAZ) file, with how to convert it.
std::string LazRefusal(const std::string& path);

/// A file coordinate: record integer times scale plus offset, in double (the specification's
/// formula, in one place so that the writer's bounds and the tiler agree with the reader).
inline double LasCoordinate(int32_t record, double scale, double offset) {
  return static_cast<double>(record) * scale + offset;
}

/// How the writer stores positions: per axis, record = round((coordinate - offset) / scale).
struct LasGrid {
  Eigen::Vector3d scale = Eigen::Vector3d::Constant(1e-4);
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
};

/// The writer's grid for `positions` (finite): 0.1 mm, or 1 mm / 1 cm where an axis spans more
/// than 0.1 mm integers can (214 km); offsets on a 1 km grid at or just below the smallest
/// coordinate. Chosen so that the positions a LAS file reads back as choose the same grid
/// (write(read(write(x))) is byte-identical). Throws std::runtime_error naming `path` when an
/// axis spans more than 1 cm integers can (21,474 km).
LasGrid ChooseLasGrid(const std::string& path, const std::vector<Eigen::Vector3d>& positions);

/// The record integers of `p` on `grid` (p must fit, as ChooseLasGrid ensures).
Eigen::Vector3i LasQuantize(const Eigen::Vector3d& p, const LasGrid& grid);

}  // namespace hylo::io::internal
