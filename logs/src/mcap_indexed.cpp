// An MCAP file read through its summary: chunks in order of their first log time, messages
// merged across the chunks loaded, so that overlapping chunks still give log-time order.

#include <algorithm>

#include "mcap_chunk_codec.h"
#include "mcap_reader.h"

namespace hylo::logs::detail {

McapIndexedReader::McapIndexedReader(const std::string& path, McapSummary summary)
    : file_(path), summary_(std::move(summary)) {
  std::stable_sort(summary_.chunks.begin(), summary_.chunks.end(),
                   [](const McapChunkIndex& a, const McapChunkIndex& b) {
                     return a.message_start_time != b.message_start_time
                                ? a.message_start_time < b.message_start_time
                                : a.chunk_start_offset < b.chunk_start_offset;
                   });
}

void McapIndexedReader::Fail(const McapChunkIndex& index, const std::string& why) const {
  throw std::runtime_error("MCAP file '" + file_.path() + "': chunk at byte " +
                           std::to_string(index.chunk_start_offset) + ": " + why);
}

bool McapIndexedReader::Next(McapMessage* message) {
  const auto& chunks = summary_.chunks;
  // A chunk may hold messages older than the oldest pending one: load every chunk that starts
  // no later than it before yielding it.
  while (next_chunk_ < chunks.size() &&
         (pending_.empty() || chunks[next_chunk_].message_start_time <= pending_.top().log_time)) {
    LoadChunk(chunks[next_chunk_++]);
  }
  if (pending_.empty()) {
    current_.reset();
    return false;
  }
  const Pending& top = pending_.top();
  message->channel = &summary_.channels.at(top.channel_id);
  message->log_time = top.log_time;
  message->data = top.buffer->data() + top.at;
  message->size = top.size;
  current_ = top.buffer;
  pending_.pop();
  return true;
}

void McapIndexedReader::LoadChunk(const McapChunkIndex& index) {
  if (index.chunk_length > (uint64_t{1} << 31)) Fail(index, "larger than 2 GB: corrupt");
  raw_.resize(index.chunk_length);
  if (!file_.ReadAt(index.chunk_start_offset, raw_.data(), raw_.size())) Fail(index, "cut short");
  if (raw_[0] != kMcapChunk || LoadLe(&raw_[1], 8) != index.chunk_length - kMcapRecordPrefix) {
    Fail(index, "no chunk record where the summary says");
  }
  const uint8_t* content = raw_.data() + kMcapRecordPrefix;
  const uint64_t length = index.chunk_length - kMcapRecordPrefix;
  McapChunkHeader header;
  try {
    header = ParseMcapChunkHeader(content, length);
  } catch (const McapError& e) {
    Fail(index, e.what());
  }
  if (header.records_size > length - header.records_at) Fail(index, "records past its end");
  auto records = std::make_shared<std::vector<uint8_t>>();
  std::string why;
  if (!DecompressMcapChunk(header.compression, content + header.records_at, header.records_size,
                           header.uncompressed_size, true, records.get(), &why)) {
    Fail(index, why);
  }
  if (header.uncompressed_crc != 0 &&
      Crc32(records->data(), records->size()) != header.uncompressed_crc) {
    Fail(index, "its CRC does not match its records");
  }
  const std::vector<uint8_t>& r = *records;
  std::size_t pos = 0;
  try {
    while (pos < r.size()) {
      if (r.size() - pos < kMcapRecordPrefix) Fail(index, "a record is cut");
      const uint8_t op = r[pos];
      const uint64_t n = LoadLe(&r[pos + 1], 8);
      if (n > r.size() - pos - kMcapRecordPrefix) Fail(index, "a record is cut");
      const uint8_t* at = &r[pos + kMcapRecordPrefix];
      if (op == kMcapMessage) {
        const McapMessageRecord m = ParseMcapMessage(at, n);
        if (summary_.channels.count(m.channel_id) == 0) Fail(index, "a message of no channel");
        pending_.push({m.log_time, loaded_++, m.channel_id, records,
                       static_cast<std::size_t>(m.data - r.data()),
                       static_cast<std::size_t>(m.size)});
      } else if (op == kMcapChannel) {
        McapChannel c = ParseMcapChannel(at, n);
        summary_.channels.emplace(c.id, std::move(c));
      } else if (op == kMcapSchema) {
        McapSchema s = ParseMcapSchema(at, n);
        if (s.id != 0) summary_.schemas.emplace(s.id, std::move(s));
      }
      pos += kMcapRecordPrefix + n;
    }
  } catch (const McapError& e) {
    Fail(index, e.what());
  }
}

}  // namespace hylo::logs::detail
