#pragma once
// Private to hylo_logs: the MCAP container (mcap.dev/spec), the records hylo reads and writes.
//
// A file is <magic><Header><data section>[<summary section>][<summary offsets>]<Footer><magic>,
// every record <opcode u8><content length u64><content>, integers little-endian, strings and
// maps with a u32 byte length first. Messages sit in the data section, usually inside Chunk
// records (their records compressed with zstd or lz4 frames, or stored as they are), each
// chunk followed by one Message Index record per channel. The summary repeats every Schema and
// Channel and adds a Chunk Index per chunk and the Statistics; the Footer says where it starts.
// A recorder that is killed leaves the data section without Data End, summary and Footer.

#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace hylo::logs::detail {

constexpr uint8_t kMcapMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
constexpr std::size_t kMcapMagicBytes = sizeof(kMcapMagic);
constexpr std::size_t kMcapRecordPrefix = 9;  // opcode + u64 content length
constexpr std::size_t kMcapFooterContent = 20;

enum McapOp : uint8_t {
  kMcapHeader = 0x01,
  kMcapFooter = 0x02,
  kMcapSchema = 0x03,
  kMcapChannel = 0x04,
  kMcapMessage = 0x05,
  kMcapChunk = 0x06,
  kMcapMessageIndex = 0x07,
  kMcapChunkIndex = 0x08,
  kMcapAttachment = 0x09,
  kMcapAttachmentIndex = 0x0A,
  kMcapStatistics = 0x0B,
  kMcapMetadata = 0x0C,
  kMcapMetadataIndex = 0x0D,
  kMcapSummaryOffset = 0x0E,
  kMcapDataEnd = 0x0F,
};

/// A record's content that does not hold its fields.
class McapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// CRC-32 (the IEEE polynomial, as zlib computes it) of `n` bytes, continuing `crc` (0 to start).
/// Carry-less multiplication where the processor has it (crc32.cpp).
uint32_t Crc32(const uint8_t* data, std::size_t n, uint32_t crc = 0);
/// The same with tables only: the reference the fast path is tested against.
uint32_t Crc32Tables(const uint8_t* data, std::size_t n, uint32_t crc = 0);

inline uint64_t LoadLe(const uint8_t* p, std::size_t bytes) {
  uint64_t v = 0;
  for (std::size_t i = bytes; i-- > 0;) v = v << 8 | p[i];
  return v;
}

/// The fields of one record's content, read in order with bounds checks (McapError).
class McapFields {
 public:
  McapFields(const uint8_t* data, uint64_t size) : data_(data), size_(size) {}
  uint8_t U8() { return static_cast<uint8_t>(Fixed(1)); }
  uint16_t U16() { return static_cast<uint16_t>(Fixed(2)); }
  uint32_t U32() { return static_cast<uint32_t>(Fixed(4)); }
  uint64_t U64() { return Fixed(8); }
  std::string String() {
    const auto [p, n] = Bytes(U32());
    return std::string(reinterpret_cast<const char*>(p), n);
  }
  /// `n` bytes in place.
  std::pair<const uint8_t*, uint64_t> Bytes(uint64_t n) {
    Need(n);
    const uint8_t* p = data_ + pos_;
    pos_ += n;
    return {p, n};
  }
  std::map<std::string, std::string> StringMap() {
    McapFields entries(Bytes(U32()));
    std::map<std::string, std::string> map;
    while (entries.remaining() > 0) {
      std::string key = entries.String();
      map[std::move(key)] = entries.String();
    }
    return map;
  }
  std::map<uint16_t, uint64_t> U16U64Map() {
    McapFields entries(Bytes(U32()));
    std::map<uint16_t, uint64_t> map;
    while (entries.remaining() > 0) {
      const uint16_t key = entries.U16();
      map[key] = entries.U64();
    }
    return map;
  }
  uint64_t remaining() const { return size_ - pos_; }
  uint64_t position() const { return pos_; }

 private:
  explicit McapFields(std::pair<const uint8_t*, uint64_t> bytes)
      : data_(bytes.first), size_(bytes.second) {}
  void Need(uint64_t n) const {
    if (n > size_ - pos_) throw McapError("a record's fields run past its end");
  }
  uint64_t Fixed(std::size_t n) {
    Need(n);
    const uint64_t v = LoadLe(data_ + pos_, n);
    pos_ += n;
    return v;
  }

  const uint8_t* data_;
  uint64_t size_;
  uint64_t pos_ = 0;
};

struct McapSchema {
  uint16_t id = 0;
  std::string name;      ///< e.g. "sensor_msgs/msg/Imu"
  std::string encoding;  ///< "ros2msg", ...
  std::string data;      ///< the definition
};

struct McapChannel {
  uint16_t id = 0;
  uint16_t schema_id = 0;  ///< 0: no schema
  std::string topic;
  std::string message_encoding;  ///< "cdr", ...
  std::map<std::string, std::string> metadata;
};

/// A Message record's content; `data` points into it.
struct McapMessageRecord {
  uint16_t channel_id = 0;
  uint32_t sequence = 0;
  uint64_t log_time = 0;
  uint64_t publish_time = 0;
  const uint8_t* data = nullptr;
  uint64_t size = 0;
};

/// A Chunk record's fields before its records; `records_at` is where they start in the content.
struct McapChunkHeader {
  uint64_t message_start_time = 0;
  uint64_t message_end_time = 0;
  uint64_t uncompressed_size = 0;
  uint32_t uncompressed_crc = 0;  ///< 0: not computed
  std::string compression;        ///< "", "zstd" or "lz4"
  uint64_t records_size = 0;      ///< compressed bytes
  uint64_t records_at = 0;
};

struct McapChunkIndex {
  uint64_t message_start_time = 0;
  uint64_t message_end_time = 0;
  uint64_t chunk_start_offset = 0;                     ///< file offset of the Chunk record
  uint64_t chunk_length = 0;                           ///< with opcode and length
  std::map<uint16_t, uint64_t> message_index_offsets;  ///< channel -> Message Index record
  uint64_t message_index_length = 0;
  std::string compression;
  uint64_t compressed_size = 0;
  uint64_t uncompressed_size = 0;
};

struct McapStatistics {
  uint64_t message_count = 0;
  uint16_t schema_count = 0;
  uint32_t channel_count = 0;
  uint32_t attachment_count = 0;
  uint32_t metadata_count = 0;
  uint32_t chunk_count = 0;
  uint64_t message_start_time = 0;
  uint64_t message_end_time = 0;
  std::map<uint16_t, uint64_t> channel_message_counts;
};

struct McapFooter {
  uint64_t summary_start = 0;         ///< 0: no summary
  uint64_t summary_offset_start = 0;  ///< 0: no summary offsets
  uint32_t summary_crc = 0;           ///< 0: not computed
};

// Each parses one record's content; McapError when the fields do not fit.
McapSchema ParseMcapSchema(const uint8_t* content, uint64_t size);
McapChannel ParseMcapChannel(const uint8_t* content, uint64_t size);
McapMessageRecord ParseMcapMessage(const uint8_t* content, uint64_t size);
/// The fields before the records; the records may be cut (a chunk cut by the end of the file):
/// `records_size` is what the chunk announces, the caller checks what it holds.
McapChunkHeader ParseMcapChunkHeader(const uint8_t* content, uint64_t size);
McapChunkIndex ParseMcapChunkIndex(const uint8_t* content, uint64_t size);
McapStatistics ParseMcapStatistics(const uint8_t* content, uint64_t size);
McapFooter ParseMcapFooter(const uint8_t* content, uint64_t size);

}  // namespace hylo::logs::detail
