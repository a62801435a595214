// MCAP record contents, field by field as the specification lists them.

#include <cstring>

#include "mcap_format.h"

namespace hylo::logs::detail {
McapSchema ParseMcapSchema(const uint8_t* content, uint64_t size) {
  McapFields f(content, size);
  McapSchema s;
  s.id = f.U16();
  s.name = f.String();
  s.encoding = f.String();
  const auto [p, n] = f.Bytes(f.U32());
  s.data.assign(reinterpret_cast<const char*>(p), n);
  return s;
}

McapChannel ParseMcapChannel(const uint8_t* content, uint64_t size) {
  McapFields f(content, size);
  McapChannel c;
  c.id = f.U16();
  c.schema_id = f.U16();
  c.topic = f.String();
  c.message_encoding = f.String();
  c.metadata = f.StringMap();
  return c;
}

McapMessageRecord ParseMcapMessage(const uint8_t* content, uint64_t size) {
  McapFields f(content, size);
  McapMessageRecord m;
  m.channel_id = f.U16();
  m.sequence = f.U32();
  m.log_time = f.U64();
  m.publish_time = f.U64();
  m.data = content + f.position();
  m.size = f.remaining();
  return m;
}

McapChunkHeader ParseMcapChunkHeader(const uint8_t* content, uint64_t size) {
  McapFields f(content, size);
  McapChunkHeader c;
  c.message_start_time = f.U64();
  c.message_end_time = f.U64();
  c.uncompressed_size = f.U64();
  c.uncompressed_crc = f.U32();
  c.compression = f.String();
  c.records_size = f.U64();
  c.records_at = f.position();
  return c;
}

McapChunkIndex ParseMcapChunkIndex(const uint8_t* content, uint64_t size) {
  McapFields f(content, size);
  McapChunkIndex c;
  c.message_start_time = f.U64();
  c.message_end_time = f.U64();
  c.chunk_start_offset = f.U64();
  c.chunk_length = f.U64();
  c.message_index_offsets = f.U16U64Map();
  c.message_index_length = f.U64();
  c.compression = f.String();
  c.compressed_size = f.U64();
  c.uncompressed_size = f.U64();
  return c;
}

McapStatistics ParseMcapStatistics(const uint8_t* content, uint64_t size) {
  McapFields f(content, size);
  McapStatistics s;
  s.message_count = f.U64();
  s.schema_count = f.U16();
  s.channel_count = f.U32();
  s.attachment_count = f.U32();
  s.metadata_count = f.U32();
  s.chunk_count = f.U32();
  s.message_start_time = f.U64();
  s.message_end_time = f.U64();
  s.channel_message_counts = f.U16U64Map();
  return s;
}

McapFooter ParseMcapFooter(const uint8_t* content, uint64_t size) {
  McapFields f(content, size);
  McapFooter footer;
  footer.summary_start = f.U64();
  footer.summary_offset_start = f.U64();
  footer.summary_crc = f.U32();
  return footer;
}

}  // namespace hylo::logs::detail
