#pragma once
// Private to hylo_io: a ROS bag v2.0 file read record by record from its start, without its
// index. rosbag_storage reads a bag only through the index written when the recording is
// closed, so a recording that was killed (no index; the last chunk open or cut) or a file cut
// short cannot be opened with it; the records themselves are all there up to the damage.
//
// Format (wiki.ros.org/Bags/Format/2.0): the line "#ROSBAG V2.0\n", then records, each
// <header_len u32><header><data_len u32><data>, a header being fields <len u32><name>=<value>.
// Field `op` gives the kind: 0x03 bag header, 0x05 chunk (fields `compression` none | bz2 |
// lz4 and `size`, the uncompressed length; its data are connection and message records),
// 0x07 connection (fields `conn`, `topic`; data: a header with `type`, `md5sum`, ...), 0x02
// message data (fields `conn` and `time`, u32 s + u32 ns; data: the serialized message),
// 0x04 index data and 0x06 chunk info (the index, skipped). Integers are little-endian.
// rosbag writes a chunk's header with size 0 and data length 0 when it opens the chunk and
// fills them in when it closes it: a chunk whose recording was killed keeps those zeros.

#include <cstdint>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace hylo::logs::detail {

/// One connection (topic and message type) of a bag, from its connection record.
struct BagConnection {
  std::string topic;
  std::string type;    ///< e.g. "sensor_msgs/Imu"
  std::string md5sum;  ///< of the message definition
};

/// One message data record. `data` points into the scanner's buffer: valid until Next().
struct BagMessageRecord {
  const BagConnection* connection = nullptr;
  int64_t receive_ns = 0;  ///< the record's time (when the recorder received it), ns
  const uint8_t* data = nullptr;
  uint32_t size = 0;  ///< serialized message bytes
};

/// True when `path` starts with the bag v2.0 version line.
bool HasBagV2Magic(const std::string& path);

/// Walks a bag's records in file order, one chunk in memory at a time (decompressed), and
/// yields its messages. Stops at the end of the file or at the first record that is cut or
/// unreadable; what was read before is kept.
class BagRecordScanner {
 public:
  /// Throws std::runtime_error naming `path` when it cannot be opened or lacks the version line.
  explicit BagRecordScanner(const std::string& path);

  /// The next complete message; false at the end or at the first damaged record.
  bool Next(BagMessageRecord* record);

  /// Every connection seen so far, by id.
  const std::map<uint32_t, BagConnection>& connections() const { return connections_; }
  uint64_t file_bytes() const { return file_bytes_; }
  /// File offset just past the last record read whole (a message whose place in the file is
  /// known, or a record outside chunks).
  uint64_t readable_bytes() const { return good_end_; }
  /// After Next() returned false: why the walk stopped ("" at a clean end of file).
  const std::string& stop_reason() const { return stop_reason_; }

 private:
  bool NextInChunk(BagMessageRecord* record);
  bool LoadChunk(uint64_t data_offset, uint32_t data_len, const std::string& compression,
                 uint32_t size);
  bool ReadAt(uint64_t offset, void* out, std::size_t n);
  bool Stop(const std::string& reason);
  void AddConnection(uint32_t id, const std::string& topic, const uint8_t* data, uint32_t size);

  std::string path_;
  std::ifstream file_;
  uint64_t file_bytes_ = 0;
  uint64_t next_record_ = 0;  // file offset of the next record outside chunks
  uint64_t good_end_ = 0;
  bool stopped_ = false;
  std::string stop_reason_;
  std::map<uint32_t, BagConnection> connections_;
  // The chunk being walked: its records (decompressed), where they start in the file (for
  // uncompressed chunks) and whether the chunk was cut or never closed.
  std::vector<uint8_t> chunk_;
  std::size_t chunk_pos_ = 0;
  bool in_chunk_ = false;
  bool chunk_damaged_ = false;
  bool chunk_open_ = false;
  bool chunk_compressed_ = false;
  uint64_t chunk_data_offset_ = 0;
  uint64_t chunk_end_ = 0;
};

}  // namespace hylo::logs::detail
