#pragma once
// Internal to hylo::io: the PCD v0.7 header, shared by the reader (pcd_read.cpp) and its
// parser (pcd_header.cpp).

#include <cstddef>
#include <fstream>
#include <string>
#include <vector>

#include "cloud_fields.h"

namespace hylo::io::internal {

struct PcdField {
  std::string name;
  ScalarType type;
  std::size_t count = 1;
  std::size_t offset = 0;  ///< bytes from the start of a point record (binary layout)
  int slot = kNone;
};

struct PcdHeader {
  std::vector<PcdField> fields;
  std::size_t width = 0;
  std::size_t height = 1;
  std::size_t points = 0;
  std::string data;            ///< ascii, binary or binary_compressed
  std::size_t point_step = 0;  ///< bytes per point record
  std::size_t FieldBytes(const PcdField& f) const { return f.type.size * f.count; }
};

/// Reads the header up to and including its DATA line; `in` is left at the first body byte.
/// Throws naming the file for a malformed header.
PcdHeader ReadPcdHeader(const std::string& path, std::ifstream* in);

/// The header of a binary PCD with float32 x y z only (pcd_write.cpp's layout).
std::string PcdXyzFloatHeader(std::size_t points);

}  // namespace hylo::io::internal
