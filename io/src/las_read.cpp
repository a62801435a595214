// LAS reader (1.0-1.4, point data record formats 0-10), read in chunks (cloud_stream.h): x y z
// (record integers times scale plus offset, in double), intensity, classification as labels, and
// normals when extra bytes are described as such. ReadLas drains one stream.

#include <algorithm>
#include <cstring>

#include "cloud_fields.h"
#include "cloud_streams.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/cloud_stream.h"
#include "las_format.h"

namespace hylo::io {
namespace {

using internal::LasHeader;

template <typename T>
T Get(const uint8_t* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

double ExtraValue(const uint8_t* record, const internal::LasExtraScalar& s) {
  const double raw = s.type == 9 ? Get<float>(record + s.offset) : Get<double>(record + s.offset);
  return raw * s.scale + s.add;
}

// Field names in record order, for CloudFileInfo (what `hylo info` and tests see).
std::vector<std::string> FieldNames(const LasHeader& h) {
  const int f = h.point_format;
  std::vector<std::string> names = {"x", "y", "z", "intensity", "return", "classification"};
  if (f >= 6) names.emplace_back("scanner_channel");
  for (const char* n : {"scan_angle", "user_data", "point_source_id"}) names.emplace_back(n);
  if (f != 0 && f != 2) names.emplace_back("gps_time");
  if (f == 2 || f == 3 || f == 5 || f == 7 || f == 8 || f == 10) {
    for (const char* n : {"red", "green", "blue"}) names.emplace_back(n);
  }
  if (f == 8 || f == 10) names.emplace_back("nir");
  if (f == 4 || f == 5 || f == 9 || f == 10) names.emplace_back("wave_packet");
  names.insert(names.end(), h.extra_names.begin(), h.extra_names.end());
  const std::size_t extra = h.record_bytes - internal::LasStandardRecordBytes(f);
  if (h.extra_names.empty() && extra > 0) {
    names.push_back("extra_bytes[" + std::to_string(extra) + "]");
  }
  return names;
}

CloudFileInfo InfoOf(const LasHeader& h) {
  CloudFileInfo info;
  info.format = "las";
  info.encoding = "LAS " + std::to_string(h.version_major) + "." + std::to_string(h.version_minor) +
                  " point format " + std::to_string(h.point_format);
  info.fields = FieldNames(h);
  info.points = static_cast<std::size_t>(h.points);
  return info;
}

class LasStream final : public CloudStream {
 public:
  explicit LasStream(const std::string& path)
      : CloudStream(path), in_(internal::OpenForReading(path)) {
    header_ = internal::ReadLasHeader(path, &in_);
    info_ = InfoOf(header_);
    present_[internal::kX] = present_[internal::kY] = present_[internal::kZ] = true;
    present_[internal::kIntensity] = present_[internal::kLabel] = true;
    present_[internal::kNx] = present_[internal::kNy] = present_[internal::kNz] =
        header_.has_normals;
    // Formats 0-5 keep the class in the low 5 bits of byte 15 (the others are flags); 6-10
    // give it byte 16 whole.
    class_byte_ = header_.point_format >= 6 ? 16 : 15;
    class_mask_ = header_.point_format >= 6 ? 0xFF : 0x1F;
  }

  bool Next(std::size_t max_points, CloudFile* chunk) override {
    *chunk = CloudFile();
    const std::size_t n = std::min<uint64_t>(max_points, header_.points - records_read_);
    if (n == 0) return false;
    const std::size_t step = header_.record_bytes;
    buffer_.resize(n * step);
    in_.read(reinterpret_cast<char*>(buffer_.data()), static_cast<std::streamsize>(buffer_.size()));
    if (static_cast<std::size_t>(in_.gcount()) != buffer_.size()) {
      ThrowFileError(path_, "truncated: the file shrank while it was read");
    }
    internal::CloudBuilder builder(path_, present_, n);
    double record[internal::kNumSlots] = {};
    for (std::size_t i = 0; i < n; ++i) {
      const uint8_t* r = buffer_.data() + i * step;
      for (int k = 0; k < 3; ++k) {
        record[k] =
            internal::LasCoordinate(Get<int32_t>(r + 4 * k), header_.scale[k], header_.offset[k]);
      }
      record[internal::kIntensity] = Get<uint16_t>(r + 12);
      record[internal::kLabel] = r[class_byte_] & class_mask_;
      if (header_.has_normals) {
        for (int k = 0; k < 3; ++k) {
          record[internal::kNx + k] = ExtraValue(r, header_.normals[static_cast<std::size_t>(k)]);
        }
      }
      builder.Add(record);
    }
    *chunk = builder.Finish();
    records_read_ += n;
    return true;
  }

 private:
  std::ifstream in_;
  LasHeader header_;
  bool present_[internal::kNumSlots] = {};
  std::size_t class_byte_ = 15;
  uint8_t class_mask_ = 0x1F;
  std::vector<uint8_t> buffer_;
};

}  // namespace

std::unique_ptr<CloudStream> internal::OpenLasStream(const std::string& path) {
  return std::make_unique<LasStream>(path);
}

CloudFile ReadLas(const std::string& path) { return ReadAll(internal::OpenLasStream(path).get()); }

CloudFileInfo ReadLasInfo(const std::string& path) {
  std::ifstream in = internal::OpenForReading(path);
  return InfoOf(internal::ReadLasHeader(path, &in));
}

}  // namespace hylo::io
