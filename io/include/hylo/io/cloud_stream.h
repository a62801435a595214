#pragma once
// A point cloud file read in chunks, so that a map larger than memory can be processed
// (`hylo tile`), and the one decoder behind ReadCloud: reading a whole file is draining its
// stream in one chunk.
//
// Memory per encoding while streaming (chunk of n points):
//  - PCD ascii/binary, PLY ascii/binary, KITTI .bin: O(n) (records are read in file order);
//  - PCD binary_compressed: the body is one LZF block that stores each field after the other
//    (all x, then all y, ...). LZF refers back at most 8 KiB, so each needed field is decoded
//    by its own cursor over the block with an 8 KiB history: O(n) memory, but the block is
//    decompressed up to the end of each field read (x y z of an x-y-z file: 1 + 2 + 3 = 6
//    field lengths instead of 3, ~2x the work of one pass). Whole-file reads decompress the
//    block once instead.

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <memory>
#include <string>

#include "hylo/common/point_types.h"
#include "hylo/io/cloud_io.h"

namespace hylo::io {

class CloudStream {
 public:
  /// Opens `path` (format by extension, as ReadCloud) and reads its header. Throws
  /// std::runtime_error naming the file and the reason (as ReadCloud), including a file
  /// shorter than its header promises when that can be told from its size.
  static std::unique_ptr<CloudStream> Open(const std::string& path);

  virtual ~CloudStream() = default;

  /// Replaces `*chunk` by the next at most `max_points` records (> 0), non-finite ones dropped
  /// and counted in chunk->dropped_non_finite; attributes as ReadCloud. Returns false, with an
  /// empty chunk, once every record was read. Throws naming the file on truncated or corrupt
  /// data.
  virtual bool Next(std::size_t max_points, CloudFile* chunk) = 0;

  const CloudFileInfo& info() const { return info_; }
  const std::string& path() const { return path_; }
  /// Records consumed so far (finite or not).
  std::size_t records_read() const { return records_read_; }

 protected:
  explicit CloudStream(std::string path) : path_(std::move(path)) {}
  std::string path_;
  CloudFileInfo info_;
  std::size_t records_read_ = 0;
};

/// Every remaining record of `stream` in one CloudFile.
CloudFile ReadAll(CloudStream* stream);

/// A binary PCD of float32 x y z written in chunks, for clouds that never sit in memory
/// whole: the points go to a body file beside `path`, and Commit() writes header and body
/// into `path` atomically (io::AtomicFile). Without Commit nothing is written.
class PcdXyzWriter {
 public:
  /// Throws std::runtime_error naming the file when the body file cannot be created.
  explicit PcdXyzWriter(std::string path);
  ~PcdXyzWriter();
  PcdXyzWriter(const PcdXyzWriter&) = delete;
  PcdXyzWriter& operator=(const PcdXyzWriter&) = delete;

  void Add(const PointCloud& points);
  /// Throws naming the file when it cannot be written (nothing is left behind).
  void Commit();
  std::size_t points() const { return points_; }

 private:
  std::string path_;
  std::string body_path_;
  std::ofstream body_;
  std::size_t points_ = 0;
};

}  // namespace hylo::io
