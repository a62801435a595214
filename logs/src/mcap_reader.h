#pragma once
// Private to hylo_logs: reading an MCAP file (mcap_format.h), two ways.
//  - Through its summary (McapIndexedReader): the Chunk Index records say where every chunk is
//    and which log times it holds; chunks are loaded in order of their first log time and their
//    messages merged, so messages come in log-time order even where chunks overlap, with about
//    two chunks in memory: the next chunk is read, decompressed and checked on a second thread
//    while the caller decodes the messages of the current one.
//  - Record by record from the start (McapLinearScanner), in file order: for a file written
//    without a summary, and for a recording that was killed or cut (no Footer, the last chunk
//    cut), read up to its last complete message.

#include <cstdint>
#include <fstream>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <queue>
#include <set>
#include <string>
#include <vector>

#include "mcap_format.h"

namespace hylo::logs::detail {

/// An MCAP file open for reading at offsets.
class McapFile {
 public:
  /// Throws std::runtime_error naming `path` when it cannot be opened or does not start with
  /// the MCAP magic.
  explicit McapFile(const std::string& path);
  const std::string& path() const { return path_; }
  uint64_t size() const { return size_; }
  /// False when [offset, offset + n) is not inside the file or cannot be read.
  bool ReadAt(uint64_t offset, void* out, uint64_t n);

 private:
  std::string path_;
  std::ifstream in_;
  uint64_t size_ = 0;
};

/// What the summary says, when the file has one.
struct McapSummary {
  std::map<uint16_t, McapSchema> schemas;
  std::map<uint16_t, McapChannel> channels;
  std::vector<McapChunkIndex> chunks;
  std::optional<McapStatistics> statistics;
};

/// How a file ends.
enum class McapEnd {
  kSummary,    ///< Footer and a readable summary
  kNoSummary,  ///< Footer without a summary (a writer's choice): read record by record
  kDamaged,    ///< no Footer, or a summary that cannot be read: read record by record
};

/// Reads the Footer and the summary; `*damage` says what is wrong for kDamaged.
McapEnd ReadMcapSummary(McapFile* file, McapSummary* summary, std::string* damage);

/// Per channel: message count and first / last log time, from the Message Index records after
/// each chunk (no chunk is decompressed). False when a chunk has none or they cannot be read.
struct McapChannelTimes {
  uint64_t count = 0;
  uint64_t first = ~uint64_t{0};
  uint64_t last = 0;
};
bool ReadMcapMessageIndexes(McapFile* file, const std::vector<McapChunkIndex>& chunks,
                            std::map<uint16_t, McapChannelTimes>* times);

/// One message; `data` stays valid until the next call of the reader that gave it.
struct McapMessage {
  const McapChannel* channel = nullptr;
  uint64_t log_time = 0;
  const uint8_t* data = nullptr;
  uint64_t size = 0;
};

/// Schema name of a channel ("" without a schema).
std::string McapSchemaName(const std::map<uint16_t, McapSchema>& schemas, const McapChannel& c);

/// Walks the data section in file order, one chunk in memory at a time (decompressed), and
/// yields its messages. Stops at Data End, at the end of the file or at the first record that is
/// cut or unreadable; what was read before is kept.
class McapLinearScanner {
 public:
  /// Throws like McapFile.
  explicit McapLinearScanner(const std::string& path);

  /// The next complete message; false at the end or at the first damaged record.
  bool Next(McapMessage* message);

  const std::map<uint16_t, McapChannel>& channels() const { return channels_; }
  const std::map<uint16_t, McapSchema>& schemas() const { return schemas_; }
  /// Chunk compressions seen ("" for stored chunks).
  const std::set<std::string>& compressions() const { return compressions_; }
  uint64_t file_bytes() const { return file_.size(); }
  /// File offset just past the last record read whole.
  uint64_t readable_bytes() const { return good_end_; }
  /// After Next() returned false: why the walk stopped ("" at Data End or a clean end of file).
  const std::string& stop_reason() const { return stop_reason_; }

 private:
  bool NextInChunk(McapMessage* message);
  bool LoadChunk(uint64_t content_at, uint64_t length);
  bool Stop(const std::string& reason);
  bool Yield(const uint8_t* content, uint64_t size, McapMessage* message);
  bool AddDefinition(uint8_t op, const uint8_t* content, uint64_t size);

  McapFile file_;
  uint64_t next_record_ = kMcapMagicBytes;
  uint64_t good_end_ = kMcapMagicBytes;
  bool stopped_ = false;
  std::string stop_reason_;
  std::map<uint16_t, McapChannel> channels_;
  std::map<uint16_t, McapSchema> schemas_;
  std::set<std::string> compressions_;
  std::vector<uint8_t> record_;  // the current record outside chunks (or a chunk's raw bytes)
  std::vector<uint8_t> chunk_;   // the current chunk's records, decompressed
  std::size_t chunk_pos_ = 0;
  bool in_chunk_ = false;
  bool chunk_cut_ = false;
  bool chunk_stored_ = false;      // records stored uncompressed: each has a file offset
  uint64_t chunk_records_at_ = 0;  // file offset of a stored chunk's records
  uint64_t chunk_end_ = 0;         // file offset past the chunk record
};

/// Reads a file with a summary in log-time order (ties: chunk order, then record order).
/// Next() throws std::runtime_error naming the file when a chunk turns out corrupt.
class McapIndexedReader {
 public:
  McapIndexedReader(const std::string& path, McapSummary summary);

  bool Next(McapMessage* message);

  const std::map<uint16_t, McapChannel>& channels() const { return summary_.channels; }
  const std::map<uint16_t, McapSchema>& schemas() const { return summary_.schemas; }
  const McapSummary& summary() const { return summary_; }

 private:
  using Buffer = std::shared_ptr<const std::vector<uint8_t>>;
  struct Pending {
    uint64_t log_time;
    uint64_t order;  // chunk order, then record order: ties keep the file's order
    uint16_t channel_id;
    Buffer buffer;
    std::size_t at;
    std::size_t size;
    bool operator>(const Pending& o) const {
      return log_time != o.log_time ? log_time > o.log_time : order > o.order;
    }
  };

  /// A chunk's records as read, decompressed and checked, or why they could not be.
  struct ChunkRecords {
    std::shared_ptr<std::vector<uint8_t>> records;
    std::string error;
  };

  // Reads, decompresses and checks chunk `index` of the sorted list; only file_ and raw_ are
  // touched, by one call at a time (the caller waits for a read ahead before reading itself).
  ChunkRecords ReadChunk(std::size_t index);
  void LoadChunk(std::size_t index);
  [[noreturn]] void Fail(const McapChunkIndex& index, const std::string& why) const;

  McapFile file_;
  McapSummary summary_;
  std::size_t next_chunk_ = 0;
  uint64_t loaded_ = 0;
  std::priority_queue<Pending, std::vector<Pending>, std::greater<Pending>> pending_;
  Buffer current_;  // keeps the last message's bytes alive
  std::vector<uint8_t> raw_;   // the chunk record as read (ReadChunk's)
  bool read_ahead_ = false;     // a second core reads the next chunk meanwhile
  std::size_t ahead_index_ = 0;
  std::future<ChunkRecords> ahead_;  // chunk ahead_index_ being read; declared last, so its
                                     // destructor waits for the read before file_ goes
};

}  // namespace hylo::logs::detail
