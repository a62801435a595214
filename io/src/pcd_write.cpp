// PCD v0.7 writer: x y z (float32, or float64 for large coordinates, see WriteCloud), then
// the attributes the cloud has: intensity F4, normal_x/y/z F4, label I4.

#include <cstdio>
#include <sstream>
#include <utility>

#include "cloud_fields.h"
#include "hylo/io/atomic_file.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/cloud_stream.h"
#include "pcd_format.h"
#include "pcd_lzf.h"

namespace hylo::io {
namespace {

struct OutField {
  std::string name;
  char type;  ///< F or I
  int size;   ///< bytes
};

std::vector<OutField> ChooseFields(const CloudFile& cloud) {
  const int position_size = internal::NeedsDoublePositions(cloud) ? 8 : 4;
  std::vector<OutField> fields = {
      {"x", 'F', position_size}, {"y", 'F', position_size}, {"z", 'F', position_size}};
  if (!cloud.intensity.empty()) fields.push_back({"intensity", 'F', 4});
  if (!cloud.normals.empty()) {
    for (const char* name : {"normal_x", "normal_y", "normal_z"}) fields.push_back({name, 'F', 4});
  }
  if (!cloud.labels.empty()) fields.push_back({"label", 'I', 4});
  return fields;
}

std::string Header(const std::vector<OutField>& fields, std::size_t points,
                   const std::string& data) {
  std::ostringstream names, sizes, types, counts;
  for (const OutField& f : fields) {
    names << ' ' << f.name;
    sizes << ' ' << f.size;
    types << ' ' << f.type;
    counts << " 1";
  }
  std::ostringstream out;
  out << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"
      << "FIELDS" << names.str() << "\nSIZE" << sizes.str() << "\nTYPE" << types.str() << "\nCOUNT"
      << counts.str() << "\nWIDTH " << points << "\nHEIGHT 1\n"
      << "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << points << "\nDATA " << data << "\n";
  return out.str();
}

// Appends field `k` of point `i` (as listed by ChooseFields) in binary.
void AppendValue(const CloudFile& cloud, const std::vector<OutField>& fields, std::size_t k,
                 std::size_t i, std::vector<uint8_t>* out) {
  if (k < 3) {
    const double c = cloud.positions[i][static_cast<int>(k)];
    if (fields[k].size == 8) {
      internal::AppendBytes(out, c);
    } else {
      internal::AppendBytes(out, static_cast<float>(c));
    }
  } else if (fields[k].name == "intensity") {
    internal::AppendBytes(out, cloud.intensity[i]);
  } else if (fields[k].name == "label") {
    internal::AppendBytes(out, cloud.labels[i]);
  } else {  // normal_x/y/z
    internal::AppendBytes(out, cloud.normals[i][fields[k].name.back() - 'x']);
  }
}

std::string AsciiBody(const CloudFile& cloud, const std::vector<OutField>& fields) {
  std::string text;
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    for (std::size_t k = 0; k < fields.size(); ++k) {
      if (k > 0) text += ' ';
      if (k < 3) {
        const double c = cloud.positions[i][static_cast<int>(k)];
        text += fields[k].size == 8 ? internal::FormatShortest(c)
                                    : internal::FormatShortest(static_cast<float>(c));
      } else if (fields[k].name == "intensity") {
        text += internal::FormatShortest(cloud.intensity[i]);
      } else if (fields[k].name == "label") {
        text += std::to_string(cloud.labels[i]);
      } else {
        text += internal::FormatShortest(cloud.normals[i][fields[k].name.back() - 'x']);
      }
    }
    text += '\n';
  }
  return text;
}

std::vector<uint8_t> BinaryBody(const CloudFile& cloud, const std::vector<OutField>& fields,
                                bool field_major) {
  std::vector<uint8_t> out;
  const std::size_t n = cloud.positions.size();
  if (field_major) {
    for (std::size_t k = 0; k < fields.size(); ++k) {
      for (std::size_t i = 0; i < n; ++i) AppendValue(cloud, fields, k, i, &out);
    }
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < fields.size(); ++k) AppendValue(cloud, fields, k, i, &out);
    }
  }
  return out;
}

// binary_compressed: u32 compressed size, u32 uncompressed size, then the LZF stream of the
// field-major data (PCL's layout: similar values sit together, so they compress).
std::vector<uint8_t> CompressedBody(const std::string& path, const CloudFile& cloud,
                                    const std::vector<OutField>& fields) {
  const std::vector<uint8_t> raw = BinaryBody(cloud, fields, /*field_major=*/true);
  if (raw.size() > UINT32_MAX) ThrowFileError(path, "too large for binary_compressed");
  const std::vector<uint8_t> packed = internal::LzfCompress(path, raw);
  std::vector<uint8_t> out;
  internal::AppendBytes(&out, static_cast<uint32_t>(packed.size()));
  internal::AppendBytes(&out, static_cast<uint32_t>(raw.size()));
  out.insert(out.end(), packed.begin(), packed.end());
  return out;
}

}  // namespace

std::string internal::PcdXyzFloatHeader(std::size_t points) {
  return Header({{"x", 'F', 4}, {"y", 'F', 4}, {"z", 'F', 4}}, points, "binary");
}

PcdXyzWriter::PcdXyzWriter(std::string path)
    : path_(std::move(path)),
      body_path_(path_ + ".body.tmp"),
      body_(body_path_, std::ios::binary | std::ios::trunc) {
  if (!body_) ThrowFileError(body_path_, "cannot create (the body of " + path_ + ")");
}

PcdXyzWriter::~PcdXyzWriter() {
  body_.close();
  std::remove(body_path_.c_str());
}

void PcdXyzWriter::Add(const PointCloud& points) {
  static_assert(sizeof(Eigen::Vector3f) == 12, "x y z float32 records");
  body_.write(reinterpret_cast<const char*>(points.data()),
              static_cast<std::streamsize>(points.size() * sizeof(Eigen::Vector3f)));
  points_ += points.size();
}

void PcdXyzWriter::Commit() {
  body_.close();
  if (!body_) ThrowFileError(body_path_, "cannot write (disk full?)");
  AtomicFile file(path_, std::ios::out | std::ios::binary);
  file.stream() << internal::PcdXyzFloatHeader(points_);
  std::ifstream body(body_path_, std::ios::binary);
  std::vector<char> block(std::size_t{1} << 20);
  while (body.read(block.data(), static_cast<std::streamsize>(block.size())) || body.gcount() > 0) {
    file.stream().write(block.data(), body.gcount());
  }
  file.Commit();
  std::remove(body_path_.c_str());
}

void WritePcd(const std::string& path, const CloudFile& cloud, CloudEncoding encoding) {
  internal::CheckAttributeSizes(path, cloud);
  const std::vector<OutField> fields = ChooseFields(cloud);
  const std::size_t n = cloud.positions.size();
  switch (encoding) {
    case CloudEncoding::kAscii: {
      const std::string body = AsciiBody(cloud, fields);
      internal::WriteFileOrThrow(path, Header(fields, n, "ascii") + body, {});
      return;
    }
    case CloudEncoding::kBinary:
      internal::WriteFileOrThrow(path, Header(fields, n, "binary"),
                                 BinaryBody(cloud, fields, /*field_major=*/false));
      return;
    case CloudEncoding::kBinaryCompressed:
      internal::WriteFileOrThrow(path, Header(fields, n, "binary_compressed"),
                                 CompressedBody(path, cloud, fields));
      return;
  }
}

}  // namespace hylo::io
