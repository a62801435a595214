#pragma once
// Private to hylo_logs: writing an MCAP file as rosbag2's MCAP storage does: messages in chunks
// (stored, zstd or lz4), a Message Index per channel after each chunk, then Data End and a
// summary (schemas, channels, statistics, chunk indexes, summary offsets) so that readers index
// the file from its Footer. The file appears whole at Close() or not at all (io::AtomicFile).

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "hylo/io/atomic_file.h"
#include "mcap_format.h"

namespace hylo::logs::detail {

struct McapWriterOptions {
  std::string compression;            ///< chunk compression: "" (stored), "zstd" or "lz4"
  uint64_t chunk_bytes = 768 * 1024;  ///< uncompressed records per chunk (rosbag2's default)
  std::string profile = "ros2";       ///< the Header's profile
};

class McapWriter {
 public:
  /// Throws std::runtime_error naming `path` when it cannot be created.
  McapWriter(const std::string& path, const McapWriterOptions& options);
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// Returns the schema's id (1, 2, ...).
  uint16_t AddSchema(const std::string& name, const std::string& encoding, const std::string& data);
  /// Returns the channel's id (0, 1, ...).
  uint16_t AddChannel(uint16_t schema_id, const std::string& topic, const std::string& encoding,
                      const std::map<std::string, std::string>& metadata);
  void WriteMessage(uint16_t channel_id, uint64_t log_time, const uint8_t* data, std::size_t size);
  /// Writes the last chunk, the summary and the footer, and moves the file into place. Throws
  /// std::runtime_error naming the file on an I/O error (no file is left then).
  void Close();

  uint64_t message_count() const { return statistics_.message_count; }

 private:
  void FlushChunk();
  void Write(const std::vector<uint8_t>& bytes);

  std::string path_;
  McapWriterOptions options_;
  io::AtomicFile out_;
  uint64_t offset_ = 0;         // bytes written so far
  std::vector<uint8_t> chunk_;  // records of the open chunk, uncompressed
  uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::map<uint16_t, std::vector<std::pair<uint64_t, uint64_t>>> chunk_index_;  // (time, offset)
  std::map<uint16_t, uint32_t> sequence_;
  std::vector<std::vector<uint8_t>> schema_records_, channel_records_;  // for the summary
  std::vector<std::vector<uint8_t>> chunk_index_records_;
  McapStatistics statistics_;
  std::vector<uint8_t> compressed_;
  bool closed_ = false;
};

}  // namespace hylo::logs::detail
