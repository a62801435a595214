// An MCAP file walked record by record from its start, as a recording killed before its
// summary was written must be read.

#include <algorithm>

#include "mcap_chunk_codec.h"
#include "mcap_reader.h"

namespace hylo::logs::detail {
namespace {

// Records hylo reads whole (chunks, schemas, channels, messages outside chunks) stay far below
// this in any recording; a longer one is corrupt data, never an allocation.
constexpr uint64_t kMaxRecordBytes = uint64_t{1} << 31;

}  // namespace

McapLinearScanner::McapLinearScanner(const std::string& path) : file_(path) {}

bool McapLinearScanner::Stop(const std::string& reason) {
  stopped_ = true;
  stop_reason_ = reason;
  in_chunk_ = false;
  std::vector<uint8_t>().swap(chunk_);
  std::vector<uint8_t>().swap(record_);
  return false;
}

bool McapLinearScanner::AddDefinition(uint8_t op, const uint8_t* content, uint64_t size) {
  try {
    if (op == kMcapSchema) {
      McapSchema s = ParseMcapSchema(content, size);
      if (s.id != 0) schemas_.emplace(s.id, std::move(s));
    } else {
      McapChannel c = ParseMcapChannel(content, size);
      channels_.emplace(c.id, std::move(c));
    }
  } catch (const McapError&) {
    return Stop(op == kMcapSchema ? "a schema record is corrupt" : "a channel record is corrupt");
  }
  return true;
}

bool McapLinearScanner::Yield(const uint8_t* content, uint64_t size, McapMessage* message) {
  McapMessageRecord m;
  try {
    m = ParseMcapMessage(content, size);
  } catch (const McapError&) {
    return Stop("a message record is corrupt");
  }
  const auto it = channels_.find(m.channel_id);
  if (it == channels_.end()) return Stop("a message names an unknown channel");
  message->channel = &it->second;
  message->log_time = m.log_time;
  message->data = m.data;
  message->size = m.size;
  return true;
}

bool McapLinearScanner::Next(McapMessage* message) {
  while (!stopped_) {
    if (in_chunk_) {
      if (NextInChunk(message)) return true;
      continue;
    }
    if (next_record_ == file_.size()) return Stop("");
    uint8_t prefix[kMcapRecordPrefix];
    if (!file_.ReadAt(next_record_, prefix, sizeof(prefix))) return Stop("a record is cut");
    const uint8_t op = prefix[0];
    const uint64_t length = LoadLe(prefix + 1, 8);
    const uint64_t content_at = next_record_ + kMcapRecordPrefix;
    if (op == kMcapDataEnd || op == kMcapFooter) {  // the data section is whole
      good_end_ = file_.size();
      return Stop("");
    }
    if (op == kMcapChunk) {
      if (!LoadChunk(content_at, length)) return false;
      continue;
    }
    if (length > file_.size() - content_at) return Stop("the last record is cut");
    next_record_ = content_at + length;
    if (op == kMcapSchema || op == kMcapChannel || op == kMcapMessage) {
      if (length > kMaxRecordBytes) return Stop("a record larger than 2 GB: corrupt");
      record_.resize(length);
      if (!file_.ReadAt(content_at, record_.data(), length)) return Stop("a record cannot be read");
      good_end_ = next_record_;
      if (op == kMcapMessage) {
        if (Yield(record_.data(), length, message)) return true;
        continue;
      }
      if (!AddDefinition(op, record_.data(), length)) return false;
    }
    good_end_ = next_record_;  // header, message indexes, attachments, metadata: skipped
  }
  return false;
}

bool McapLinearScanner::LoadChunk(uint64_t content_at, uint64_t length) {
  const uint64_t available = file_.size() - content_at;
  const bool complete = length <= available;
  const uint64_t n = complete ? length : available;
  if (n > kMaxRecordBytes) return Stop("a chunk larger than 2 GB: corrupt");
  record_.resize(n);
  if (!file_.ReadAt(content_at, record_.data(), n)) return Stop("a chunk cannot be read");
  McapChunkHeader header;
  try {
    header = ParseMcapChunkHeader(record_.data(), n);
  } catch (const McapError&) {
    return Stop(complete ? "a chunk record is corrupt" : "the last chunk is cut");
  }
  const uint64_t held = n - header.records_at;
  if (complete && header.records_size > held) return Stop("a chunk record is corrupt");
  const bool whole = complete || header.records_size <= held;
  std::string why;
  if (!DecompressMcapChunk(header.compression, record_.data() + header.records_at,
                           std::min(held, header.records_size), header.uncompressed_size, whole,
                           &chunk_, &why)) {
    return Stop("a chunk cannot be decoded: " + why);
  }
  if (whole && header.uncompressed_crc != 0 &&
      Crc32(chunk_.data(), chunk_.size()) != header.uncompressed_crc) {
    return Stop("a chunk's CRC does not match its records");
  }
  compressions_.insert(header.compression);
  chunk_pos_ = 0;
  in_chunk_ = true;
  chunk_cut_ = !whole;
  chunk_stored_ = header.compression.empty();
  chunk_records_at_ = content_at + header.records_at;
  chunk_end_ = content_at + n;
  next_record_ = chunk_end_;
  return true;
}

bool McapLinearScanner::NextInChunk(McapMessage* message) {
  while (chunk_.size() - chunk_pos_ >= kMcapRecordPrefix) {
    const uint8_t op = chunk_[chunk_pos_];
    const uint64_t length = LoadLe(&chunk_[chunk_pos_ + 1], 8);
    if (length > chunk_.size() - chunk_pos_ - kMcapRecordPrefix) break;
    const uint8_t* content = &chunk_[chunk_pos_ + kMcapRecordPrefix];
    chunk_pos_ += kMcapRecordPrefix + length;
    // In a stored chunk every record's place in the file is known.
    if (chunk_stored_) good_end_ = chunk_records_at_ + chunk_pos_;
    if (op == kMcapMessage) {
      if (Yield(content, length, message)) return true;
      return false;
    }
    if ((op == kMcapSchema || op == kMcapChannel) && !AddDefinition(op, content, length)) {
      return false;
    }
  }
  const bool whole = chunk_pos_ == chunk_.size();
  in_chunk_ = false;
  if (!chunk_cut_ && whole) {
    good_end_ = chunk_end_;
    return false;
  }
  if (chunk_cut_) return Stop("the last chunk is cut");
  return Stop("a chunk holds a corrupt record");
}

}  // namespace hylo::logs::detail
