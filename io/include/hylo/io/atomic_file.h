#pragma once
// Output files that appear complete or not at all. A run killed half-way, a full disk or a
// writer that throws must not leave a truncated map or trajectory that a later tool reads as
// if it were whole: the bytes go to a temporary file beside the target, which Commit() renames
// over it (rename is atomic within one file system). Without Commit the temporary is removed
// and the target is left as it was.

#include <fstream>
#include <ios>
#include <string>

namespace hylo::io {

class AtomicFile {
 public:
  /// Opens the temporary file. Throws std::runtime_error naming `path` when it cannot.
  explicit AtomicFile(const std::string& path, std::ios::openmode mode = std::ios::out);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return out_; }
  /// Flushes, checks that every write succeeded and moves the file into place. Throws
  /// std::runtime_error naming `path` (disk full, I/O error) and leaves no file behind.
  void Commit();

 private:
  std::string path_;
  std::string temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

/// `text` then `bytes` into `path`, atomically (AtomicFile).
void WriteFileAtomically(const std::string& path, const std::string& text,
                         const char* bytes = nullptr, std::size_t size = 0);

}  // namespace hylo::io
