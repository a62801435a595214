// MCAP records serialized field by field in the specification's order.

#include "mcap_writer.h"

#include <algorithm>
#include <stdexcept>

#include "mcap_chunk_codec.h"

namespace hylo::logs::detail {
namespace {

/// One record appended to a buffer: opcode, a length patched in at End(), the fields.
class Record {
 public:
  Record(uint8_t op, std::vector<uint8_t>* out) : out_(out), start_(out->size()) {
    out_->push_back(op);
    U64(0);
  }
  void U8(uint8_t v) { out_->push_back(v); }
  void U16(uint16_t v) { Le(v, 2); }
  void U32(uint32_t v) { Le(v, 4); }
  void U64(uint64_t v) { Le(v, 8); }
  void String(const std::string& s) {
    U32(static_cast<uint32_t>(s.size()));
    out_->insert(out_->end(), s.begin(), s.end());
  }
  void Bytes(const uint8_t* p, std::size_t n) { out_->insert(out_->end(), p, p + n); }
  void StringMap(const std::map<std::string, std::string>& map) {
    std::size_t bytes = 0;
    for (const auto& [k, v] : map) bytes += 8 + k.size() + v.size();
    U32(static_cast<uint32_t>(bytes));
    for (const auto& [k, v] : map) {
      String(k);
      String(v);
    }
  }
  void U16U64Map(const std::map<uint16_t, uint64_t>& map) {
    U32(static_cast<uint32_t>(map.size() * 10));
    for (const auto& [k, v] : map) {
      U16(k);
      U64(v);
    }
  }
  /// Patches the content length in.
  void End() {
    const uint64_t length = out_->size() - start_ - kMcapRecordPrefix;
    for (int i = 0; i < 8; ++i) (*out_)[start_ + 1 + i] = static_cast<uint8_t>(length >> (8 * i));
  }

 private:
  void Le(uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out_->push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  std::vector<uint8_t>* out_;
  std::size_t start_;
};

}  // namespace

McapWriter::McapWriter(const std::string& path, const McapWriterOptions& options)
    : path_(path), options_(options), out_(path, std::ios::out | std::ios::binary) {
  std::vector<uint8_t> head(kMcapMagic, kMcapMagic + kMcapMagicBytes);
  Record header(kMcapHeader, &head);
  header.String(options_.profile);
  header.String("hylo");
  header.End();
  Write(head);
}

void McapWriter::Write(const std::vector<uint8_t>& bytes) {
  out_.stream().write(reinterpret_cast<const char*>(bytes.data()),
                      static_cast<std::streamsize>(bytes.size()));
  offset_ += bytes.size();
}

uint16_t McapWriter::AddSchema(const std::string& name, const std::string& encoding,
                               const std::string& data) {
  const uint16_t id = static_cast<uint16_t>(schema_records_.size() + 1);
  std::vector<uint8_t> bytes;
  Record r(kMcapSchema, &bytes);
  r.U16(id);
  r.String(name);
  r.String(encoding);
  r.U32(static_cast<uint32_t>(data.size()));
  r.Bytes(reinterpret_cast<const uint8_t*>(data.data()), data.size());
  r.End();
  // In the chunk too, so that a reader walking a file cut before its summary meets it.
  chunk_.insert(chunk_.end(), bytes.begin(), bytes.end());
  schema_records_.push_back(std::move(bytes));
  ++statistics_.schema_count;
  return id;
}

uint16_t McapWriter::AddChannel(uint16_t schema_id, const std::string& topic,
                                const std::string& encoding,
                                const std::map<std::string, std::string>& metadata) {
  const uint16_t id = static_cast<uint16_t>(channel_records_.size());
  std::vector<uint8_t> bytes;
  Record r(kMcapChannel, &bytes);
  r.U16(id);
  r.U16(schema_id);
  r.String(topic);
  r.String(encoding);
  r.StringMap(metadata);
  r.End();
  chunk_.insert(chunk_.end(), bytes.begin(), bytes.end());
  channel_records_.push_back(std::move(bytes));
  ++statistics_.channel_count;
  statistics_.channel_message_counts[id] = 0;
  return id;
}

void McapWriter::WriteMessage(uint16_t channel_id, uint64_t log_time, const uint8_t* data,
                              std::size_t size) {
  if (closed_) throw std::logic_error("MCAP file '" + path_ + "': write after Close()");
  if (chunk_index_.empty()) chunk_start_ = chunk_end_ = log_time;
  chunk_start_ = std::min(chunk_start_, log_time);
  chunk_end_ = std::max(chunk_end_, log_time);
  chunk_index_[channel_id].emplace_back(log_time, chunk_.size());
  Record r(kMcapMessage, &chunk_);
  r.U16(channel_id);
  r.U32(sequence_[channel_id]++);
  r.U64(log_time);
  r.U64(log_time);  // publish time: unknown, so the log time (as the specification asks)
  r.Bytes(data, size);
  r.End();
  if (statistics_.message_count++ == 0) {
    statistics_.message_start_time = statistics_.message_end_time = log_time;
  }
  statistics_.message_start_time = std::min(statistics_.message_start_time, log_time);
  statistics_.message_end_time = std::max(statistics_.message_end_time, log_time);
  ++statistics_.channel_message_counts[channel_id];
  if (chunk_.size() >= options_.chunk_bytes) FlushChunk();
}

void McapWriter::FlushChunk() {
  if (chunk_.empty()) return;
  CompressMcapChunk(options_.compression, chunk_.data(), chunk_.size(), &compressed_);
  McapChunkIndex index;
  index.message_start_time = chunk_index_.empty() ? 0 : chunk_start_;
  index.message_end_time = chunk_index_.empty() ? 0 : chunk_end_;
  index.chunk_start_offset = offset_;
  index.compression = options_.compression;
  index.compressed_size = compressed_.size();
  index.uncompressed_size = chunk_.size();
  std::vector<uint8_t> bytes;
  Record chunk(kMcapChunk, &bytes);
  chunk.U64(index.message_start_time);
  chunk.U64(index.message_end_time);
  chunk.U64(chunk_.size());
  chunk.U32(Crc32(chunk_.data(), chunk_.size()));
  chunk.String(options_.compression);
  chunk.U64(compressed_.size());
  chunk.Bytes(compressed_.data(), compressed_.size());
  chunk.End();
  index.chunk_length = bytes.size();
  Write(bytes);
  bytes.clear();
  for (const auto& [channel, entries] : chunk_index_) {
    index.message_index_offsets[channel] = offset_ + bytes.size();
    Record r(kMcapMessageIndex, &bytes);
    r.U16(channel);
    r.U32(static_cast<uint32_t>(entries.size() * 16));
    for (const auto& [time, at] : entries) {
      r.U64(time);
      r.U64(at);
    }
    r.End();
  }
  index.message_index_length = bytes.size();
  Write(bytes);
  std::vector<uint8_t> record;
  Record r(kMcapChunkIndex, &record);
  r.U64(index.message_start_time);
  r.U64(index.message_end_time);
  r.U64(index.chunk_start_offset);
  r.U64(index.chunk_length);
  r.U16U64Map(index.message_index_offsets);
  r.U64(index.message_index_length);
  r.String(index.compression);
  r.U64(index.compressed_size);
  r.U64(index.uncompressed_size);
  r.End();
  chunk_index_records_.push_back(std::move(record));
  ++statistics_.chunk_count;
  chunk_.clear();
  chunk_index_.clear();
}

void McapWriter::Close() {
  if (closed_) return;
  closed_ = true;
  FlushChunk();
  std::vector<uint8_t> end;
  Record data_end(kMcapDataEnd, &end);
  data_end.U32(0);  // data section CRC: not computed
  data_end.End();
  Write(end);
  // The summary, grouped by opcode, each group then listed in the summary offsets.
  const uint64_t summary_start = offset_;
  std::vector<uint8_t> summary;
  std::vector<std::pair<uint8_t, std::pair<uint64_t, uint64_t>>> groups;
  const auto group = [&](uint8_t op, const std::vector<std::vector<uint8_t>>& records) {
    if (records.empty()) return;
    const uint64_t start = summary_start + summary.size();
    for (const auto& r : records) summary.insert(summary.end(), r.begin(), r.end());
    groups.push_back({op, {start, summary_start + summary.size() - start}});
  };
  group(kMcapSchema, schema_records_);
  group(kMcapChannel, channel_records_);
  std::vector<uint8_t> statistics;
  Record s(kMcapStatistics, &statistics);
  s.U64(statistics_.message_count);
  s.U16(statistics_.schema_count);
  s.U32(statistics_.channel_count);
  s.U32(0);  // attachments
  s.U32(0);  // metadata
  s.U32(statistics_.chunk_count);
  s.U64(statistics_.message_start_time);
  s.U64(statistics_.message_end_time);
  s.U16U64Map(statistics_.channel_message_counts);
  s.End();
  group(kMcapStatistics, {statistics});
  group(kMcapChunkIndex, chunk_index_records_);
  const uint64_t offsets_start = summary_start + summary.size();
  for (const auto& [op, extent] : groups) {
    Record o(kMcapSummaryOffset, &summary);
    o.U8(op);
    o.U64(extent.first);
    o.U64(extent.second);
    o.End();
  }
  // The Footer by hand: its CRC covers the summary, the summary offsets and the footer's own
  // opcode, length and offsets, so the length must be in place before the CRC is computed.
  const auto le = [&](uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) summary.push_back(static_cast<uint8_t>(v >> (8 * i)));
  };
  summary.push_back(kMcapFooter);
  le(kMcapFooterContent, 8);
  le(summary_start, 8);
  le(offsets_start, 8);
  le(Crc32(summary.data(), summary.size()), 4);
  summary.insert(summary.end(), kMcapMagic, kMcapMagic + kMcapMagicBytes);
  Write(summary);
  out_.Commit();
}

}  // namespace hylo::logs::detail
