// PLY writer: one vertex element, x y z (float, or double for large coordinates, see
// WriteCloud), then nx ny nz, intensity (float) and label (int) when the cloud has them.

#include <sstream>

#include "cloud_fields.h"
#include "hylo/io/cloud_io.h"

namespace hylo::io {
namespace {

std::string Header(const CloudFile& cloud, bool ascii, bool double_positions) {
  std::ostringstream out;
  out << "ply\nformat " << (ascii ? "ascii" : "binary_little_endian") << " 1.0\n"
      << "comment written by hylo\nelement vertex " << cloud.positions.size() << "\n";
  const char* position_type = double_positions ? "double" : "float";
  for (const char* axis : {"x", "y", "z"}) out << "property " << position_type << ' ' << axis << '\n';
  if (!cloud.normals.empty()) out << "property float nx\nproperty float ny\nproperty float nz\n";
  if (!cloud.intensity.empty()) out << "property float intensity\n";
  if (!cloud.labels.empty()) out << "property int label\n";
  out << "end_header\n";
  return out.str();
}

std::string AsciiBody(const CloudFile& cloud, bool double_positions) {
  std::string text;
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (k > 0) text += ' ';
      const double c = cloud.positions[i][k];
      text += double_positions ? internal::FormatShortest(c)
                               : internal::FormatShortest(static_cast<float>(c));
    }
    if (!cloud.normals.empty()) {
      for (int k = 0; k < 3; ++k) text += ' ' + internal::FormatShortest(cloud.normals[i][k]);
    }
    if (!cloud.intensity.empty()) text += ' ' + internal::FormatShortest(cloud.intensity[i]);
    if (!cloud.labels.empty()) text += ' ' + std::to_string(cloud.labels[i]);
    text += '\n';
  }
  return text;
}

std::vector<uint8_t> BinaryBody(const CloudFile& cloud, bool double_positions) {
  std::vector<uint8_t> out;
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double c = cloud.positions[i][k];
      if (double_positions) {
        internal::AppendBytes(&out, c);
      } else {
        internal::AppendBytes(&out, static_cast<float>(c));
      }
    }
    if (!cloud.normals.empty()) {
      for (int k = 0; k < 3; ++k) internal::AppendBytes(&out, cloud.normals[i][k]);
    }
    if (!cloud.intensity.empty()) internal::AppendBytes(&out, cloud.intensity[i]);
    if (!cloud.labels.empty()) internal::AppendBytes(&out, cloud.labels[i]);
  }
  return out;
}

}  // namespace

void WritePly(const std::string& path, const CloudFile& cloud, CloudEncoding encoding) {
  internal::CheckAttributeSizes(path, cloud);
  if (encoding == CloudEncoding::kBinaryCompressed) {
    ThrowFileError(path, "cannot write: PLY has no compressed encoding");
  }
  const bool ascii = encoding == CloudEncoding::kAscii;
  const bool double_positions = internal::NeedsDoublePositions(cloud);
  const std::string header = Header(cloud, ascii, double_positions);
  if (ascii) {
    internal::WriteFileOrThrow(path, header + AsciiBody(cloud, double_positions), {});
  } else {
    internal::WriteFileOrThrow(path, header, BinaryBody(cloud, double_positions));
  }
}

}  // namespace hylo::io
