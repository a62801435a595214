// PCD v0.7 reader: ascii, binary (point-major) and binary_compressed (LZF, field-major), read
// in chunks (cloud_stream.h); ReadPcd drains one stream.

#include <algorithm>
#include <cstdlib>

#include "cloud_fields.h"
#include "cloud_streams.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/cloud_stream.h"
#include "pcd_format.h"
#include "pcd_lzf.h"

namespace hylo::io {
namespace {

using internal::PcdField;
using internal::PcdHeader;
using internal::ScalarKind;


[[noreturn]] void Truncated(const std::string& path, std::size_t have, const std::string& promise) {
  ThrowFileError(path,
                 "truncated: " + std::to_string(have) + " data bytes, header promises " + promise);
}

std::string PointsOf(const PcdHeader& header) {
  return std::to_string(header.points) + " points of " + std::to_string(header.point_step) +
         " bytes";
}

uint32_t ReadU32(const uint8_t* p) {
  return static_cast<uint32_t>(internal::DecodeScalar(p, {ScalarKind::kUnsigned, 4}, false));
}

class PcdStream final : public CloudStream {
 public:
  // `whole_block`: a binary_compressed block is decompressed at once (one pass, the whole
  // block in memory: what a whole-file read needs anyway) instead of by field cursors.
  PcdStream(const std::string& path, bool whole_block)
      : CloudStream(path), in_(internal::OpenForReading(path)) {
    header_ = internal::ReadPcdHeader(path, &in_);
    info_.format = "pcd";
    info_.encoding = header_.data;
    info_.points = header_.points;
    for (const PcdField& f : header_.fields) {
      info_.fields.push_back(f.name);
      if (f.slot != internal::kNone) present_[f.slot] = true;
    }
    internal::CloudBuilder check(path, present_, 0);  // x, y and z must be there
    if (header_.data == "ascii") OpenAscii();
    if (header_.data == "binary") OpenBinary();
    if (header_.data == "binary_compressed") OpenCompressed(whole_block);
  }

  bool Next(std::size_t max_points, CloudFile* chunk) override {
    *chunk = CloudFile();
    const std::size_t n = std::min(max_points, header_.points - records_read_);
    if (n == 0) return false;
    if (header_.data == "ascii") {
      ReadAscii(n, chunk);
    } else if (header_.data == "binary") {
      ReadBinary(n, chunk);
    } else {
      ReadCompressed(n, chunk);
    }
    records_read_ += n;
    return true;
  }

 private:
  // Each value takes at least one character: more per point than the body holds is a
  // truncated file, found before a per-point buffer is sized from the header's counts.
  void OpenAscii() {
    if (header_.points == 0) return;  // nothing to read, whatever the counts say
    std::size_t values_per_point = 0;
    for (const PcdField& f : header_.fields) values_per_point += f.count;
    const std::size_t body = internal::BytesLeft(&in_);
    if (values_per_point > body) {
      Truncated(path_, body, std::to_string(values_per_point) + " ascii values per point");
    }
  }

  void OpenBinary() {
    const std::size_t body = internal::BytesLeft(&in_);
    if (body / header_.point_step < header_.points) Truncated(path_, body, PointsOf(header_));
  }

  void OpenCompressed(bool whole_block) {
    std::size_t body = internal::BytesLeft(&in_);
    uint8_t sizes[8];
    if (body < 8 || !in_.read(reinterpret_cast<char*>(sizes), 8)) {
      Truncated(path_, body, "an 8-byte size block");
    }
    body -= 8;
    const uint32_t compressed_size = ReadU32(sizes);
    const uint32_t uncompressed_size = ReadU32(sizes + 4);
    if (body < compressed_size) {
      Truncated(path_, body, std::to_string(compressed_size) + " compressed bytes");
    }
    const std::size_t expected = header_.points * header_.point_step;
    if (header_.points > UINT32_MAX / header_.point_step || uncompressed_size != expected) {
      ThrowFileError(path_, "corrupt: compressed block expands to " +
                                std::to_string(uncompressed_size) + " bytes, header implies " +
                                std::to_string(expected));
    }
    // Field-major: all values of field 0, then all of field 1, ...
    std::size_t offset = 0;
    for (const PcdField& f : header_.fields) {
      field_start_.push_back(offset);
      offset += header_.points * header_.FieldBytes(f);
    }
    if (whole_block) {
      std::vector<uint8_t> packed(compressed_size);
      in_.read(reinterpret_cast<char*>(packed.data()), compressed_size);
      block_ = internal::LzfDecompress(path_, packed.data(), compressed_size, expected);
      return;
    }
    const std::streamoff data = in_.tellg();
    cursors_.resize(header_.fields.size());
    for (std::size_t k = 0; k < header_.fields.size(); ++k) {
      if (header_.fields[k].slot == internal::kNone) continue;
      cursors_[k] = std::make_unique<internal::LzfCursor>(path_, data, compressed_size, expected);
      cursors_[k]->Read(nullptr, field_start_[k]);
    }
  }

  // Decodes n records where field k of record i starts at base[k] + i * stride[k].
  void Decode(std::size_t n, const std::vector<const uint8_t*>& base,
              const std::vector<std::size_t>& stride, CloudFile* chunk) const {
    internal::CloudBuilder builder(path_, present_, n);
    double record[internal::kNumSlots] = {};
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < header_.fields.size(); ++k) {
        const PcdField& f = header_.fields[k];
        if (f.slot == internal::kNone) continue;
        record[f.slot] = internal::DecodeScalar(base[k] + i * stride[k], f.type, false);
      }
      builder.Add(record);
    }
    *chunk = builder.Finish();
  }

  void ReadBinary(std::size_t n, CloudFile* chunk) {
    buffer_.resize(n * header_.point_step);
    in_.read(reinterpret_cast<char*>(buffer_.data()), static_cast<std::streamsize>(buffer_.size()));
    if (static_cast<std::size_t>(in_.gcount()) != buffer_.size()) {
      Truncated(path_, records_read_ * header_.point_step + in_.gcount(), PointsOf(header_));
    }
    std::vector<const uint8_t*> base;
    std::vector<std::size_t> stride;
    for (const PcdField& f : header_.fields) {
      base.push_back(buffer_.data() + f.offset);
      stride.push_back(header_.point_step);
    }
    Decode(n, base, stride, chunk);
  }

  void ReadCompressed(std::size_t n, CloudFile* chunk) {
    std::vector<const uint8_t*> base;
    std::vector<std::size_t> stride;
    field_chunks_.resize(header_.fields.size());
    for (std::size_t k = 0; k < header_.fields.size(); ++k) {
      const std::size_t size = header_.FieldBytes(header_.fields[k]);
      stride.push_back(size);
      if (header_.fields[k].slot == internal::kNone) {
        base.push_back(nullptr);  // never read
        continue;
      }
      if (!block_.empty()) {
        base.push_back(block_.data() + field_start_[k] + records_read_ * size);
        continue;
      }
      field_chunks_[k].resize(n * size);
      cursors_[k]->Read(field_chunks_[k].data(), n * size);
      base.push_back(field_chunks_[k].data());
    }
    Decode(n, base, stride, chunk);
  }

  // One point per line; blank lines are skipped. A line with the wrong number of values is an
  // error naming the line (counted from the first data line).
  void ReadAscii(std::size_t n, CloudFile* chunk) {
    std::size_t values_per_point = 0;
    for (const PcdField& f : header_.fields) values_per_point += f.count;
    // The header's count is not checked against the file's size here: reserve modestly.
    internal::CloudBuilder builder(path_, present_, std::min<std::size_t>(n, 1 << 20));
    std::vector<double> values(values_per_point);
    double record[internal::kNumSlots] = {};
    std::string line;
    for (std::size_t done = 0; done < n;) {
      if (!std::getline(in_, line)) {
        ThrowFileError(path_, "truncated: " + std::to_string(records_read_ + done) +
                                  " ascii points, header promises " +
                                  std::to_string(header_.points));
      }
      ++ascii_line_;
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      ParseLine(line, &values);
      std::size_t v = 0;
      for (const PcdField& f : header_.fields) {
        if (f.slot != internal::kNone) record[f.slot] = internal::AsDeclared(values[v], f.type);
        v += f.count;
      }
      builder.Add(record);
      ++done;
    }
    *chunk = builder.Finish();
  }

  void ParseLine(const std::string& line, std::vector<double>* values) const {
    const char* cursor = line.c_str();
    std::size_t count = 0;
    for (char* end = nullptr;; cursor = end) {
      const double value = std::strtod(cursor, &end);
      if (end == cursor) break;
      if (count < values->size()) (*values)[count] = value;
      ++count;
    }
    const bool junk = line.find_first_not_of(" \t\r", cursor - line.c_str()) != std::string::npos;
    if (count != values->size() || junk) {
      ThrowFileError(path_, "malformed or truncated ascii data line " +
                                std::to_string(ascii_line_) + ": expected " +
                                std::to_string(values->size()) + " numbers, found " +
                                std::to_string(count) + (junk ? " and text" : ""));
    }
  }

  std::ifstream in_;
  PcdHeader header_;
  bool present_[internal::kNumSlots] = {};
  std::vector<uint8_t> buffer_;                                // binary: one chunk of records
  std::vector<std::size_t> field_start_;                       // compressed: byte of each field
  std::vector<uint8_t> block_;                                 // compressed, whole: the block
  std::vector<std::unique_ptr<internal::LzfCursor>> cursors_;  // compressed, streamed
  std::vector<std::vector<uint8_t>> field_chunks_;             // ... one chunk of each field
  std::size_t ascii_line_ = 0;
};

}  // namespace

std::unique_ptr<CloudStream> internal::OpenPcdStream(const std::string& path, bool whole) {
  return std::make_unique<PcdStream>(path, whole);
}

CloudFile ReadPcd(const std::string& path) {
  return ReadAll(internal::OpenPcdStream(path, /*whole=*/true).get());
}

CloudFileInfo ReadPcdInfo(const std::string& path) {
  std::ifstream in = internal::OpenForReading(path);
  const PcdHeader header = internal::ReadPcdHeader(path, &in);
  CloudFileInfo info;
  info.format = "pcd";
  info.encoding = header.data;
  info.points = header.points;
  for (const PcdField& f : header.fields) info.fields.push_back(f.name);
  return info;
}

}  // namespace hylo::io
