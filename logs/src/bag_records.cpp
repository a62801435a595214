#include "bag_records.h"

#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "bag_chunk_codec.h"

namespace hylo::logs::detail {
namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr std::size_t kMagicBytes = sizeof(kMagic) - 1;
constexpr uint8_t kOpMessage = 0x02;
constexpr uint8_t kOpChunk = 0x05;
constexpr uint8_t kOpConnection = 0x07;
// Record headers hold a few short fields (a connection's data holds the long message
// definition, not its header): a longer header is corrupt data, not a record.
constexpr uint32_t kMaxHeaderBytes = 1 << 20;

using Fields = std::map<std::string, std::string>;

uint32_t U32(const uint8_t* p) {
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}

/// Parses <len u32><name>=<value> fields; false when they do not fill `n` bytes exactly.
bool ParseFields(const uint8_t* p, std::size_t n, Fields* fields) {
  fields->clear();
  std::size_t i = 0;
  while (i < n) {
    if (n - i < 4) return false;
    const uint32_t len = U32(p + i);
    i += 4;
    if (len > n - i) return false;
    const char* field = reinterpret_cast<const char*>(p + i);
    const void* eq = std::memchr(field, '=', len);
    if (eq == nullptr) return false;
    const std::size_t name_len = static_cast<const char*>(eq) - field;
    (*fields)[std::string(field, name_len)] = std::string(field + name_len + 1, len - name_len - 1);
    i += len;
  }
  return true;
}

bool FieldU32(const Fields& f, const char* name, uint32_t* value) {
  const auto it = f.find(name);
  if (it == f.end() || it->second.size() != 4) return false;
  *value = U32(reinterpret_cast<const uint8_t*>(it->second.data()));
  return true;
}

int Op(const Fields& f) {
  const auto it = f.find("op");
  return it == f.end() || it->second.size() != 1 ? -1 : static_cast<uint8_t>(it->second[0]);
}

/// One record inside a chunk buffer: header fields and where its data lies.
struct InnerRecord {
  Fields fields;
  std::size_t data = 0;
  uint32_t data_len = 0;
  std::size_t end = 0;
};

/// The record at `pos` of `buffer`; false when it is cut or malformed.
bool ParseInner(const std::vector<uint8_t>& buffer, std::size_t pos, InnerRecord* record) {
  const std::size_t n = buffer.size();
  if (n - pos < 4) return false;
  const uint32_t header_len = U32(&buffer[pos]);
  if (header_len > kMaxHeaderBytes || n - pos - 4 < std::size_t{header_len} + 4) return false;
  if (!ParseFields(&buffer[pos + 4], header_len, &record->fields)) return false;
  record->data_len = U32(&buffer[pos + 4 + header_len]);
  record->data = pos + 8 + header_len;
  if (record->data_len > n - record->data) return false;
  record->end = record->data + record->data_len;
  return true;
}

}  // namespace

bool HasBagV2Magic(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[kMagicBytes] = {};
  return in.read(head, kMagicBytes) && std::memcmp(head, kMagic, kMagicBytes) == 0;
}

BagRecordScanner::BagRecordScanner(const std::string& path)
    : path_(path), file_(path, std::ios::binary) {
  std::error_code ec;
  file_bytes_ = std::filesystem::file_size(path, ec);
  if (!file_ || ec) throw std::runtime_error("bag '" + path + "': cannot be opened");
  if (!HasBagV2Magic(path)) {
    throw std::runtime_error("bag '" + path + "': not a ROS bag (format 2.0)");
  }
  next_record_ = good_end_ = kMagicBytes;
}

bool BagRecordScanner::ReadAt(uint64_t offset, void* out, std::size_t n) {
  if (offset > file_bytes_ || n > file_bytes_ - offset) return false;
  file_.clear();
  file_.seekg(static_cast<std::streamoff>(offset));
  return static_cast<bool>(file_.read(static_cast<char*>(out), static_cast<std::streamsize>(n)));
}

bool BagRecordScanner::Stop(const std::string& reason) {
  stopped_ = true;
  stop_reason_ = reason;
  in_chunk_ = false;
  std::vector<uint8_t>().swap(chunk_);
  return false;
}

void BagRecordScanner::AddConnection(uint32_t id, const std::string& topic, const uint8_t* data,
                                     uint32_t size) {
  if (connections_.count(id) > 0) return;  // each connection is written once per chunk file
  Fields details;
  ParseFields(data, size, &details);  // type and md5sum, when the data is readable
  connections_[id] = {topic, details["type"], details["md5sum"]};
}

bool BagRecordScanner::Next(BagMessageRecord* record) {
  while (!stopped_) {
    if (in_chunk_) {
      if (NextInChunk(record)) return true;
      continue;
    }
    if (next_record_ == file_bytes_) return Stop("");
    uint8_t len_bytes[4];
    if (!ReadAt(next_record_, len_bytes, 4)) return Stop("a record header is cut");
    const uint32_t header_len = U32(len_bytes);
    if (header_len > kMaxHeaderBytes) return Stop("a record header is corrupt (too long)");
    std::vector<uint8_t> header(header_len + 4);  // the header and the data length after it
    if (!ReadAt(next_record_ + 4, header.data(), header.size())) {
      return Stop("a record header is cut");
    }
    Fields fields;
    if (!ParseFields(header.data(), header_len, &fields)) return Stop("a record header is corrupt");
    const uint32_t data_len = U32(&header[header_len]);
    const uint64_t data_offset = next_record_ + 8 + header_len;
    const int op = Op(fields);
    if (op == kOpChunk) {
      uint32_t size = 0;
      if (!FieldU32(fields, "size", &size)) return Stop("a chunk header is corrupt");
      if (!LoadChunk(data_offset, data_len, fields["compression"], size)) return false;
      continue;
    }
    if (data_len > file_bytes_ - std::min(data_offset, file_bytes_)) {
      return Stop("the last record is cut");
    }
    if (op < 0) return Stop("a record without its kind (op)");
    next_record_ = data_offset + data_len;
    if (op == kOpConnection) {
      uint32_t id = 0;
      std::vector<uint8_t> data(data_len);
      if (!FieldU32(fields, "conn", &id) || !ReadAt(data_offset, data.data(), data_len)) {
        return Stop("a connection record is corrupt");
      }
      AddConnection(id, fields["topic"], data.data(), data_len);
    }
    good_end_ = next_record_;  // bag header, index data, chunk info: nothing to yield
  }
  return false;
}

bool BagRecordScanner::LoadChunk(uint64_t data_offset, uint32_t data_len,
                                 const std::string& compression, uint32_t size) {
  // A chunk never closed keeps data length 0: its records run to the end of the file.
  const bool open = data_len == 0;
  const uint64_t available = file_bytes_ - std::min(data_offset, file_bytes_);
  const bool complete = !open && data_len <= available;
  const uint64_t n = complete ? data_len : available;
  if (n > (uint64_t{1} << 31)) return Stop("a chunk larger than 2 GB: corrupt");
  std::vector<uint8_t> raw(static_cast<std::size_t>(n));
  if (!ReadAt(data_offset, raw.data(), raw.size())) return Stop("a chunk cannot be read");
  std::string why;
  if (!DecompressChunk(compression, raw.data(), raw.size(), open ? 0 : size, complete, &chunk_,
                       &why)) {
    return Stop("a chunk cannot be decoded: " + why);
  }
  chunk_pos_ = 0;
  in_chunk_ = true;
  chunk_damaged_ = !complete;
  chunk_open_ = open;
  chunk_compressed_ = compression != "none";
  chunk_data_offset_ = data_offset;
  chunk_end_ = data_offset + n;
  next_record_ = chunk_end_;
  return true;
}

bool BagRecordScanner::NextInChunk(BagMessageRecord* record) {
  InnerRecord inner;
  while (chunk_pos_ < chunk_.size() && ParseInner(chunk_, chunk_pos_, &inner)) {
    chunk_pos_ = inner.end;
    // In an uncompressed chunk every record's place in the file is known.
    if (!chunk_compressed_) good_end_ = chunk_data_offset_ + inner.end;
    const int op = Op(inner.fields);
    uint32_t id = 0;
    if (op == kOpConnection && FieldU32(inner.fields, "conn", &id)) {
      AddConnection(id, inner.fields["topic"], &chunk_[inner.data], inner.data_len);
      continue;
    }
    if (op != kOpMessage) continue;
    const auto time = inner.fields.find("time");
    const bool stamped = time != inner.fields.end() && time->second.size() == 8;
    const auto it =
        FieldU32(inner.fields, "conn", &id) ? connections_.find(id) : connections_.end();
    if (!stamped || it == connections_.end()) {
      return Stop("a message record is corrupt or names an unknown connection");
    }
    const auto* t = reinterpret_cast<const uint8_t*>(time->second.data());
    record->connection = &it->second;
    record->receive_ns = int64_t{U32(t)} * 1000000000 + int64_t{U32(t + 4)};
    record->data = &chunk_[inner.data];
    record->size = inner.data_len;
    return true;
  }
  const bool whole = chunk_pos_ == chunk_.size();
  in_chunk_ = false;
  if (!chunk_damaged_ && whole) {
    good_end_ = chunk_end_;
    return false;
  }
  if (chunk_damaged_) {
    return Stop(chunk_open_ ? "the last chunk was never closed" : "the last chunk is cut");
  }
  return Stop("a chunk holds a corrupt record");
}

}  // namespace hylo::logs::detail
