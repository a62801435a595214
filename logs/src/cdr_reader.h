#pragma once
// Private to hylo_logs: ROS 2 messages as they are serialized (OMG CDR, as the ROS 2 middlewares
// write it): a 4-byte encapsulation header (representation id, big-endian u16; options u16),
// then the fields in order, each primitive aligned to its size counted from the byte after the
// header (XCDR1: up to 8; XCDR2's plain encoding: up to 4). Strings are a u32 length that counts
// the terminating NUL, then the bytes and the NUL; sequences a u32 element count, then the
// elements; fixed arrays the elements only. Every length is checked against the bytes left
// before anything is allocated or looped over.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace hylo::logs::detail {

/// Bytes that do not hold the message: cut short, a length past the end, an unknown encoding.
class CdrError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class CdrReader {
 public:
  /// `data` starts with the encapsulation header. Throws CdrError for fewer than 4 bytes or an
  /// encapsulation other than plain CDR / plain CDR2 (either byte order).
  CdrReader(const uint8_t* data, std::size_t size) : data_(data), size_(size) {
    if (size < 4) throw CdrError("message shorter than its 4-byte CDR header");
    const unsigned id = unsigned{data[0]} << 8 | data[1];
    // 0x0000/0x0001: CDR big/little endian; 0x0006/0x0007: plain CDR2 big/little endian.
    if (id != 0x0000 && id != 0x0001 && id != 0x0006 && id != 0x0007) {
      char hex[8];
      std::snprintf(hex, sizeof(hex), "0x%04x", id);
      throw CdrError(std::string("unsupported CDR encapsulation ") + hex);
    }
    swap_ = (id & 1) == 0;  // big endian on a little-endian host
    max_align_ = id >= 0x0006 ? 4 : 8;
    pos_ = 4;
  }

  /// One primitive (integer, float, double, bool as uint8), aligned.
  template <typename T>
  T Read() {
    static_assert(std::is_arithmetic_v<T>, "primitives only");
    Align(sizeof(T));
    Need(sizeof(T));
    uint8_t bytes[sizeof(T)];
    std::memcpy(bytes, data_ + pos_, sizeof(T));
    if (swap_) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    }
    pos_ += sizeof(T);
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }

  std::string ReadString() {
    const uint32_t length = Read<uint32_t>();
    Need(length);
    const char* chars = reinterpret_cast<const char*>(data_ + pos_);
    pos_ += length;
    // The length counts the NUL; a writer that leaves it out (length 0 for "") is tolerated.
    const std::size_t n = length > 0 && chars[length - 1] == '\0' ? length - 1 : length;
    return std::string(chars, n);
  }

  /// A sequence's element count, refused when `count * min_element_bytes` exceeds what is left:
  /// a corrupt count never sizes an allocation or a loop.
  uint32_t ReadSequenceLength(std::size_t min_element_bytes) {
    const uint32_t count = Read<uint32_t>();
    if (uint64_t{count} * min_element_bytes > size_ - pos_) {
      throw CdrError("a sequence announces " + std::to_string(count) +
                     " elements, the message has " + std::to_string(size_ - pos_) + " bytes left");
    }
    return count;
  }

  /// `n` raw bytes (a uint8[] sequence's payload); valid as long as the message bytes are.
  const uint8_t* Take(std::size_t n) {
    Need(n);
    const uint8_t* at = data_ + pos_;
    pos_ += n;
    return at;
  }

  /// Skips `n` primitives of size `element_size` (a fixed array the caller does not need).
  void Skip(std::size_t n, std::size_t element_size) {
    Align(element_size);
    Need(n * element_size);
    pos_ += n * element_size;
  }

  std::size_t remaining() const { return size_ - pos_; }

 private:
  void Align(std::size_t size) {
    const std::size_t a = size < max_align_ ? size : max_align_;
    const std::size_t offset = pos_ - 4;
    const std::size_t padded = (offset + a - 1) / a * a;
    Need(padded - offset);
    pos_ = 4 + padded;
  }

  void Need(std::size_t n) const {
    if (n > size_ - pos_) {
      throw CdrError("message cut short: " + std::to_string(n) + " bytes needed at byte " +
                     std::to_string(pos_) + " of " + std::to_string(size_));
    }
  }

  const uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  bool swap_ = false;
  std::size_t max_align_ = 8;
};

}  // namespace hylo::logs::detail
