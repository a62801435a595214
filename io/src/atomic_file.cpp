#include "hylo/io/atomic_file.h"

#include <unistd.h>

#include <cstdio>
#include <stdexcept>

namespace hylo::io {

AtomicFile::AtomicFile(const std::string& path, std::ios::openmode mode)
    : path_(path), temporary_(path + ".tmp" + std::to_string(::getpid())) {
  out_.open(temporary_, mode | std::ios::out | std::ios::trunc);
  if (!out_) throw std::runtime_error("'" + path_ + "': cannot open for writing");
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::remove(temporary_.c_str());
}

void AtomicFile::Commit() {
  out_.close();
  if (!out_) {
    std::remove(temporary_.c_str());
    throw std::runtime_error("'" + path_ + "': write failed (disk full or I/O error)");
  }
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    std::remove(temporary_.c_str());
    throw std::runtime_error("'" + path_ + "': cannot move the written file into place");
  }
  committed_ = true;
}

void WriteFileAtomically(const std::string& path, const std::string& text, const char* bytes,
                         std::size_t size) {
  AtomicFile file(path, std::ios::binary);
  file.stream().write(text.data(), static_cast<std::streamsize>(text.size()));
  if (size > 0) file.stream().write(bytes, static_cast<std::streamsize>(size));
  file.Commit();
}

}  // namespace hylo::io
