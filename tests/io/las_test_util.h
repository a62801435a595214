#pragma once
// LAS files built byte by byte from the specification's offsets (LAS 1.4 R15, "Public Header
// Block" and "Point Data Records"), independently of hylo's writer, and raw field access for
// checking what the reader returns.

#include <Eigen/Core>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace hylo::io::testing {

inline std::vector<uint8_t> FileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void WriteBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

template <typename T>
T At(const std::vector<uint8_t>& bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

template <typename T>
void Put(std::vector<uint8_t>* bytes, std::size_t offset, T value) {
  std::memcpy(bytes->data() + offset, &value, sizeof(T));
}

/// The fields of a LAS header that say where and what the points are (spec offsets).
struct RawLasHeader {
  int minor = 0;
  uint32_t point_data_offset = 0;
  int format = 0;
  uint16_t record_bytes = 0;
  uint64_t points = 0;
  Eigen::Vector3d scale, offset;
};

inline RawLasHeader ParseRawHeader(const std::vector<uint8_t>& b) {
  RawLasHeader h;
  h.minor = b[25];
  h.point_data_offset = At<uint32_t>(b, 96);
  h.format = b[104];
  h.record_bytes = At<uint16_t>(b, 105);
  h.points = At<uint32_t>(b, 107);
  if (h.minor >= 4 && At<uint64_t>(b, 247) != 0) h.points = At<uint64_t>(b, 247);
  for (int k = 0; k < 3; ++k) {
    h.scale[k] = At<double>(b, 131 + 8 * k);
    h.offset[k] = At<double>(b, 155 + 8 * k);
  }
  return h;
}

/// Point i's coordinates as the specification defines them: record integer * scale + offset.
inline Eigen::Vector3d RawPosition(const std::vector<uint8_t>& b, const RawLasHeader& h,
                                   std::size_t i) {
  const std::size_t at = h.point_data_offset + i * h.record_bytes;
  Eigen::Vector3d p;
  for (int k = 0; k < 3; ++k) {
    p[k] = static_cast<double>(At<int32_t>(b, at + 4 * k)) * h.scale[k] + h.offset[k];
  }
  return p;
}

/// Bytes of each point data record format's own fields (spec tables 7-17).
inline std::size_t StandardBytes(int format) {
  static constexpr std::size_t kBytes[] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
  return kBytes[format];
}

/// One record of `format`, `record_bytes` long (the rest zero): X Y Z at 0/4/8, intensity at 12;
/// formats 0-5 put the classification byte at 15, formats 6-10 at 16; `flag_bits` go to the
/// class byte's top 3 bits (formats 0-5: synthetic, key-point, withheld).
inline std::vector<uint8_t> RawRecord(int format, std::size_t record_bytes, int32_t x, int32_t y,
                                      int32_t z, uint16_t intensity, uint8_t classification,
                                      uint8_t flag_bits = 0) {
  std::vector<uint8_t> r(record_bytes, 0);
  Put(&r, 0, x);
  Put(&r, 4, y);
  Put(&r, 8, z);
  Put(&r, 12, intensity);
  if (format < 6) {
    r[15] = static_cast<uint8_t>(classification | flag_bits << 5);
  } else {
    r[16] = classification;
  }
  return r;
}

/// A whole LAS 1.`minor` file: header of the version's size, `vlr_payloads` as VLRs (user
/// "test", record 1), then the records. Legacy and (1.4) 64-bit counts are both filled.
inline std::vector<uint8_t> RawLas(int minor, int format, std::size_t record_bytes,
                                   const Eigen::Vector3d& scale, const Eigen::Vector3d& offset,
                                   const std::vector<std::vector<uint8_t>>& records,
                                   const std::vector<std::vector<uint8_t>>& vlr_payloads = {}) {
  const std::size_t header = minor <= 2 ? 227 : (minor == 3 ? 235 : 375);
  std::vector<uint8_t> b(header, 0);
  std::memcpy(b.data(), "LASF", 4);
  b[24] = 1;
  b[25] = static_cast<uint8_t>(minor);
  Put<uint16_t>(&b, 94, static_cast<uint16_t>(header));
  Put<uint32_t>(&b, 100, static_cast<uint32_t>(vlr_payloads.size()));
  b[104] = static_cast<uint8_t>(format);
  Put<uint16_t>(&b, 105, static_cast<uint16_t>(record_bytes));
  Put<uint32_t>(&b, 107, static_cast<uint32_t>(records.size()));
  for (int k = 0; k < 3; ++k) {
    Put(&b, 131 + 8 * k, scale[k]);
    Put(&b, 155 + 8 * k, offset[k]);
  }
  if (minor >= 4) Put<uint64_t>(&b, 247, records.size());
  for (const std::vector<uint8_t>& payload : vlr_payloads) {
    std::vector<uint8_t> vlr(54, 0);
    std::memcpy(vlr.data() + 2, "test", 4);
    Put<uint16_t>(&vlr, 18, 1);
    Put<uint16_t>(&vlr, 20, static_cast<uint16_t>(payload.size()));
    b.insert(b.end(), vlr.begin(), vlr.end());
    b.insert(b.end(), payload.begin(), payload.end());
  }
  Put<uint32_t>(&b, 96, static_cast<uint32_t>(b.size()));
  for (const std::vector<uint8_t>& r : records) b.insert(b.end(), r.begin(), r.end());
  return b;
}

}  // namespace hylo::io::testing
