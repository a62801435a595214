#pragma once
// Private to hylo_logs: what a rosbag2 path is (a directory with metadata.yaml, a directory a
// killed recorder left without it, or one storage file) and its storage files merged into one
// stream in log-time order.

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "message_decode.h"
#include "rosbag2_metadata.h"
#include "storage_source.h"

namespace hylo::logs::detail {

struct Rosbag2Layout {
  std::string path;     ///< as given (named in errors)
  std::string storage;  ///< "sqlite3" or "mcap"
  std::optional<Rosbag2Metadata> metadata;
  std::vector<std::string> files;  ///< storage files, in split order
  /// rosbag2's own compression (zstd only): "" none, "file" (each storage file one zstd
  /// stream) or "message" (each message's bytes one zstd frame).
  std::string compression_mode;
  std::string damage;  ///< what is wrong with the directory itself ("" when nothing)
};

/// True when the file starts with the MCAP magic or the sqlite3 header.
bool HasRosbag2StorageMagic(const std::string& path);

/// Works out what `path` holds. Throws std::runtime_error, one line naming the path: missing,
/// metadata.yaml malformed, a storage file it names missing, an unknown storage identifier or
/// compression, a directory without metadata.yaml or storage files.
Rosbag2Layout ResolveRosbag2(const std::string& path);

/// A message's CDR bytes: as stored, or out of the zstd frame rosbag2's per-message compression
/// put them in (valid until the next call).
class MessageBytes {
 public:
  explicit MessageBytes(bool compressed) : compressed_(compressed) {}
  /// Throws std::runtime_error when a compressed message is no zstd frame stating its size.
  std::pair<const uint8_t*, std::size_t> Of(const StorageMessage& m);

 private:
  bool compressed_;
  std::vector<uint8_t> buffer_;
};

/// Every storage file open at once, merged by log time (ties: the earlier file first). Files
/// compressed whole are decompressed to temporary files first, removed with the stream.
class Rosbag2Stream {
 public:
  explicit Rosbag2Stream(const Rosbag2Layout& layout);
  ~Rosbag2Stream();
  Rosbag2Stream(const Rosbag2Stream&) = delete;
  Rosbag2Stream& operator=(const Rosbag2Stream&) = delete;

  /// The next message of any file; false when all are done.
  bool Next(StorageMessage* message);

  /// Topic name -> the types its files (and the metadata) give it.
  TopicTypes Topics() const;
  /// Every topic entry of `name` (to check its serialization).
  std::vector<StorageTopic> TopicEntries(const std::string& name) const;
  /// True when every file lists all its topics without being read (sqlite3, indexed MCAP) or
  /// metadata.yaml lists them.
  bool topics_complete() const;
  /// Non-null when the directory or a file is damaged; final once Next() has returned false.
  const LogRecovery* recovery();
  const std::vector<std::unique_ptr<StorageSource>>& sources() const { return sources_; }

 private:
  Rosbag2Layout layout_;
  std::vector<std::string> temporaries_;
  std::vector<std::unique_ptr<StorageSource>> sources_;
  std::vector<StorageMessage> heads_;
  std::vector<bool> has_head_;
  int last_ = -1;  // the source whose head was yielded last (advanced on the next call)
  bool started_ = false;
  std::size_t messages_ = 0;
  int64_t first_ns_ = 0, last_ns_ = 0;
  LogRecovery recovery_;
};

}  // namespace hylo::logs::detail
