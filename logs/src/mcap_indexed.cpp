// An MCAP file read through its summary: chunks in order of their first log time, messages
// merged across the chunks loaded, so that overlapping chunks still give log-time order. The
// next chunk's file read, decompression and CRC run on another thread while the caller decodes
// the current chunk's messages (on a machine with a second core): decompression is what a
// compressed recording costs beyond a stored one, and it need not wait for the decoding.

#include <algorithm>
#include <thread>

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
  read_ahead_ = std::thread::hardware_concurrency() > 1;
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
    LoadChunk(next_chunk_++);
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

McapIndexedReader::ChunkRecords McapIndexedReader::ReadChunk(std::size_t i) {
  const McapChunkIndex& index = summary_.chunks[i];
  ChunkRecords out;
  if (index.chunk_length > (uint64_t{1} << 31)) {
    out.error = "larger than 2 GB: corrupt";
    return out;
  }
  std::vector<uint8_t>& raw = raw_;  // reused: one ReadChunk runs at a time
  raw.resize(index.chunk_length);
  if (!file_.ReadAt(index.chunk_start_offset, raw.data(), raw.size())) {
    out.error = "cut short";
    return out;
  }
  if (raw[0] != kMcapChunk || LoadLe(&raw[1], 8) != index.chunk_length - kMcapRecordPrefix) {
    out.error = "no chunk record where the summary says";
    return out;
  }
  const uint8_t* content = raw.data() + kMcapRecordPrefix;
  const uint64_t length = index.chunk_length - kMcapRecordPrefix;
  McapChunkHeader header;
  try {
    header = ParseMcapChunkHeader(content, length);
  } catch (const McapError& e) {
    out.error = e.what();
    return out;
  }
  if (header.records_size > length - header.records_at) {
    out.error = "records past its end";
    return out;
  }
  auto records = std::make_shared<std::vector<uint8_t>>();
  if (!DecompressMcapChunk(header.compression, content + header.records_at, header.records_size,
                           header.uncompressed_size, true, records.get(), &out.error)) {
    return out;
  }
  if (header.uncompressed_crc != 0 &&
      Crc32(records->data(), records->size()) != header.uncompressed_crc) {
    out.error = "its CRC does not match its records";
    return out;
  }
  out.records = std::move(records);
  return out;
}

void McapIndexedReader::LoadChunk(std::size_t i) {
  const McapChunkIndex& index = summary_.chunks[i];
  ChunkRecords loaded;
  if (ahead_.valid() && ahead_index_ == i) {
    loaded = ahead_.get();
  } else {
    if (ahead_.valid()) ahead_.wait();  // never two readers of file_ at once
    loaded = ReadChunk(i);
  }
  if (read_ahead_ && i + 1 < summary_.chunks.size()) {
    ahead_index_ = i + 1;
    ahead_ = std::async(std::launch::async, [this, next = i + 1] { return ReadChunk(next); });
  }
  if (!loaded.error.empty()) Fail(index, loaded.error);
  const std::shared_ptr<std::vector<uint8_t>>& records = loaded.records;
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
