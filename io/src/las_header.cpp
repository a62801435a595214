// The LAS public header, VLRs and EVLRs (las_format.h): every size and position a file gives is
// checked against the file's size before anything is allocated or read from it.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "cloud_fields.h"
#include "las_format.h"

namespace hylo::io::internal {
namespace {

template <typename T>
T Get(const uint8_t* bytes, std::size_t at) {
  T value;
  std::memcpy(&value, bytes + at, sizeof(T));  // little-endian on every supported platform
  return value;
}

std::string Text(const uint8_t* bytes, std::size_t size) {
  const auto* end = static_cast<const uint8_t*>(std::memchr(bytes, 0, size));
  return std::string(reinterpret_cast<const char*>(bytes),
                     end == nullptr ? size : static_cast<std::size_t>(end - bytes));
}

std::string Version(const LasHeader& h) {
  return std::to_string(h.version_major) + "." + std::to_string(h.version_minor);
}

// Reads `size` bytes at `at` (the caller checked that they lie inside the file).
void ReadAt(const std::string& path, std::ifstream* in, uint64_t at, uint8_t* out,
            std::size_t size) {
  in->seekg(static_cast<std::streamoff>(at));
  if (!in->read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(size))) {
    ThrowFileError(path, "cannot read " + std::to_string(size) + " bytes at byte " +
                             std::to_string(at) + " (the file shrank while it was read?)");
  }
}

// Bytes of one value of an extra-bytes data type (0 for reserved types, which make the
// descriptors unusable). Types 11-30 are the deprecated 2- and 3-element arrays of 1-10.
std::size_t ExtraTypeBytes(int type, int options) {
  static constexpr std::size_t kBytes[] = {0, 1, 1, 2, 2, 4, 4, 8, 8, 4, 8};
  if (type == 0) return static_cast<std::size_t>(options);  // undocumented: options = bytes
  if (type <= 10) return kBytes[type];
  if (type <= 20) return 2 * kBytes[type - 10];
  if (type <= 30) return 3 * kBytes[type - 20];
  return 0;
}

int NormalAxis(const std::string& name) {
  const std::string n = ToLower(name);
  for (int k = 0; k < 3; ++k) {
    const std::string axis(1, static_cast<char>('x' + k));
    if (n == "normal" + axis || n == "normal_" + axis || n == "n" + axis) return k;
  }
  return -1;
}

// The Extra Bytes VLR (LASF_Spec, record 4): the descriptors' names, and where the normals are.
// Descriptors that describe more bytes than each record has are invalid (the specification's
// "extra bytes mismatch"), as are reserved data types: the extra bytes are then only skipped.
void ReadExtraBytes(const std::vector<uint8_t>& payload, LasHeader* h) {
  const std::size_t extra = h->record_bytes - LasStandardRecordBytes(h->point_format);
  std::size_t at = LasStandardRecordBytes(h->point_format), used = 0;
  std::array<bool, 3> found{};
  LasHeader parsed = *h;
  parsed.extra_names.clear();
  for (std::size_t d = 0; d + kLasExtraBytesDescriptorBytes <= payload.size();
       d += kLasExtraBytesDescriptorBytes) {
    const uint8_t* desc = payload.data() + d;
    const int type = desc[2], options = desc[3];
    const std::size_t bytes = ExtraTypeBytes(type, options);
    if (bytes == 0 || bytes > extra - used) return;
    const std::string name = Text(desc + 4, 32);
    parsed.extra_names.push_back(name);
    const int axis = NormalAxis(name);
    if (axis >= 0 && (type == 9 || type == 10)) {
      LasExtraScalar& s = parsed.normals[static_cast<std::size_t>(axis)];
      s.offset = at;
      s.type = type;
      s.scale = (options & 0x08) != 0 ? Get<double>(desc, 112) : 1.0;
      s.add = (options & 0x10) != 0 ? Get<double>(desc, 136) : 0.0;
      found[static_cast<std::size_t>(axis)] = true;
    }
    at += bytes;
    used += bytes;
  }
  parsed.has_normals = found[0] && found[1] && found[2];
  *h = parsed;
}

// VLRs lie between the header and the point data; only the Extra Bytes VLR is read.
void WalkVlrs(const std::string& path, std::ifstream* in, uint32_t count, LasHeader* h) {
  uint64_t at = h->header_bytes;
  for (uint32_t i = 0; i < count; ++i) {
    const auto fail = [&] {
      ThrowFileError(path, "VLR " + std::to_string(i + 1) + " of " + std::to_string(count) +
                               " does not fit between the header and the point data at byte " +
                               std::to_string(h->point_data_offset) +
                               " (a broken VLR count or length)");
    };
    if (h->point_data_offset - at < kLasVlrHeaderBytes) fail();
    uint8_t vlr[kLasVlrHeaderBytes];
    ReadAt(path, in, at, vlr, sizeof(vlr));
    const uint16_t length = Get<uint16_t>(vlr, 20);
    at += kLasVlrHeaderBytes;
    if (h->point_data_offset - at < length) fail();
    if (Text(vlr + 2, 16) == "LASF_Spec" && Get<uint16_t>(vlr, 18) == 4 &&
        h->record_bytes > LasStandardRecordBytes(h->point_format)) {
      std::vector<uint8_t> payload(length);
      ReadAt(path, in, at, payload.data(), length);
      ReadExtraBytes(payload, h);
    }
    at += length;
  }
}

// EVLRs (1.4) follow the point data; each is bounds-checked and skipped.
void WalkEvlrs(const std::string& path, std::ifstream* in, uint64_t start, uint32_t count,
               uint64_t points_end, uint64_t file_bytes) {
  if (count == 0) return;
  if (start < points_end) {
    ThrowFileError(path, "the first EVLR starts at byte " + std::to_string(start) +
                             ", inside the point data (which ends at byte " +
                             std::to_string(points_end) + ")");
  }
  uint64_t at = start;
  for (uint32_t i = 0; i < count; ++i) {
    if (at > file_bytes || file_bytes - at < kLasEvlrHeaderBytes) {
      ThrowFileError(path, "truncated: EVLR " + std::to_string(i + 1) + " of " +
                               std::to_string(count) + " starts at byte " + std::to_string(at) +
                               ", the file has " + std::to_string(file_bytes) + " bytes");
    }
    uint8_t evlr[kLasEvlrHeaderBytes];
    ReadAt(path, in, at, evlr, sizeof(evlr));
    const uint64_t length = Get<uint64_t>(evlr, 20);
    at += kLasEvlrHeaderBytes;
    if (file_bytes - at < length) {
      ThrowFileError(path, "truncated: EVLR " + std::to_string(i + 1) + " of " +
                               std::to_string(count) + " announces " + std::to_string(length) +
                               " bytes, the file ends " + std::to_string(file_bytes - at) +
                               " bytes after its header");
    }
    at += length;
  }
}

void CheckScaleAndOffset(const std::string& path, const LasHeader& h) {
  for (int k = 0; k < 3; ++k) {
    const std::string axis(1, static_cast<char>('X' + k));
    if (!std::isfinite(h.scale[k]) || h.scale[k] == 0.0) {
      ThrowFileError(path, axis + " scale factor is " + FormatShortest(h.scale[k]) +
                               " (must be a finite, non-zero number)");
    }
    if (!std::isfinite(h.offset[k])) {
      ThrowFileError(path,
                     axis + " offset is " + FormatShortest(h.offset[k]) + " (must be finite)");
    }
  }
}

std::size_t MinimumHeaderBytes(int minor) {
  if (minor <= 2) return kLasHeaderBytes12;
  return minor == 3 ? kLasHeaderBytes13 : kLasHeaderBytes14;
}

}  // namespace

std::size_t LasStandardRecordBytes(int format) {
  static constexpr std::size_t kBytes[] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
  return kBytes[format];
}

std::string LazRefusal(const std::string& path) {
  std::filesystem::path out(path);
  out.replace_extension(".las");
  return "LAZ (compressed LAS) is not supported; decompress it first, e.g. 'laszip -i " + path +
         " -o " + out.string() + "' or 'pdal translate " + path + " " + out.string() + "'";
}

LasHeader ReadLasHeader(const std::string& path, std::ifstream* in) {
  const uint64_t file_bytes = BytesLeft(in);
  uint8_t raw[kLasHeaderBytes14] = {};
  in->read(reinterpret_cast<char*>(raw),
           static_cast<std::streamsize>(std::min<uint64_t>(file_bytes, sizeof(raw))));
  if (file_bytes < 4 || std::memcmp(raw, "LASF", 4) != 0) {
    ThrowFileError(path, "not a LAS file (no 'LASF' signature)");
  }
  if (file_bytes < kLasHeaderBytes12) {
    ThrowFileError(
        path, "truncated: " + std::to_string(file_bytes) + " bytes, a LAS header alone has 227");
  }
  LasHeader h;
  h.version_major = raw[24];
  h.version_minor = raw[25];
  if (h.version_major != 1 || h.version_minor > 4) {
    ThrowFileError(path, "LAS " + Version(h) + " is not supported (LAS 1.0-1.4)");
  }
  h.header_bytes = Get<uint16_t>(raw, 94);
  const std::size_t minimum = MinimumHeaderBytes(h.version_minor);
  if (h.header_bytes < minimum) {
    ThrowFileError(path, "header size " + std::to_string(h.header_bytes) + " is below the " +
                             std::to_string(minimum) + " bytes of a LAS " + Version(h) + " header");
  }
  if (h.header_bytes > file_bytes) {
    ThrowFileError(path, "truncated: " + std::to_string(file_bytes) + " bytes, the header alone " +
                             "announces " + std::to_string(h.header_bytes));
  }
  const int format_byte = raw[104];
  if ((format_byte & 0xC0) != 0) ThrowFileError(path, LazRefusal(path));
  if (format_byte > kLasMaxPointFormat) {
    ThrowFileError(path, "unknown point data record format " + std::to_string(format_byte) +
                             " (LAS has 0-10)");
  }
  h.point_format = format_byte;
  h.record_bytes = Get<uint16_t>(raw, 105);
  if (h.record_bytes < LasStandardRecordBytes(h.point_format)) {
    ThrowFileError(path, "point record length " + std::to_string(h.record_bytes) +
                             " is shorter than the " +
                             std::to_string(LasStandardRecordBytes(h.point_format)) +
                             " bytes of point format " + std::to_string(h.point_format));
  }
  for (int k = 0; k < 3; ++k) {
    h.scale[k] = Get<double>(raw, 131 + 8 * k);
    h.offset[k] = Get<double>(raw, 155 + 8 * k);
  }
  CheckScaleAndOffset(path, h);
  // 1.4 counts in 64 bits; its legacy 32-bit field must then be 0 for formats 6-10 (and may be
  // for others), so the legacy count is only a fallback for writers that filled nothing else.
  h.points = Get<uint32_t>(raw, 107);
  if (h.version_minor >= 4 && Get<uint64_t>(raw, 247) != 0) h.points = Get<uint64_t>(raw, 247);
  h.point_data_offset = Get<uint32_t>(raw, 96);
  if (h.point_data_offset < h.header_bytes || h.point_data_offset > file_bytes) {
    ThrowFileError(path, "offset to point data " + std::to_string(h.point_data_offset) +
                             " lies outside bytes " + std::to_string(h.header_bytes) + ".." +
                             std::to_string(file_bytes) + " (after the header, in the file)");
  }
  const uint64_t body = file_bytes - h.point_data_offset;
  if (body / h.record_bytes < h.points) {
    ThrowFileError(path, "truncated: " + std::to_string(h.points) + " points of " +
                             std::to_string(h.record_bytes) + " bytes need " +
                             (h.points > UINT64_MAX / h.record_bytes
                                  ? std::string("more than 2^64")
                                  : std::to_string(h.points * h.record_bytes)) +
                             " bytes from byte " + std::to_string(h.point_data_offset) +
                             ", the file has " + std::to_string(body));
  }
  WalkVlrs(path, in, Get<uint32_t>(raw, 100), &h);
  if (h.version_minor >= 4) {
    WalkEvlrs(path, in, Get<uint64_t>(raw, 235), Get<uint32_t>(raw, 243),
              h.point_data_offset + h.points * h.record_bytes, file_bytes);
  }
  in->clear();
  in->seekg(static_cast<std::streamoff>(h.point_data_offset));
  return h;
}

}  // namespace hylo::io::internal
