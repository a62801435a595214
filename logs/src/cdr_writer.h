#pragma once
// Private to hylo_logs: ROS 2 messages serialized as the ROS 2 middlewares do by default (CDR,
// little endian, XCDR1 alignment; see cdr_reader.h for the rules).

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace hylo::logs::detail {

class CdrWriter {
 public:
  /// Starts the message with the encapsulation header of little-endian CDR. `reserve`: the
  /// expected size, to write large messages without reallocating.
  explicit CdrWriter(std::size_t reserve = 256) {
    static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "writes host byte order");
    bytes_.reserve(reserve + 4);
    bytes_ = {0x00, 0x01, 0x00, 0x00};
  }

  template <typename T>
  void Write(T value) {
    static_assert(std::is_arithmetic_v<T>, "primitives only");
    Align(sizeof(T));
    const std::size_t at = bytes_.size();
    bytes_.resize(at + sizeof(T));
    std::memcpy(bytes_.data() + at, &value, sizeof(T));
  }

  void WriteString(const std::string& text) {
    Write(static_cast<uint32_t>(text.size() + 1));
    bytes_.insert(bytes_.end(), text.begin(), text.end());
    bytes_.push_back(0);
  }

  void WriteSequenceLength(std::size_t count) { Write(static_cast<uint32_t>(count)); }

  void WriteBytes(const uint8_t* data, std::size_t n) {
    bytes_.insert(bytes_.end(), data, data + n);
  }

  std::vector<uint8_t> Take() { return std::move(bytes_); }

 private:
  void Align(std::size_t size) {
    const std::size_t offset = bytes_.size() - 4;
    bytes_.resize(4 + (offset + size - 1) / size * size, 0);
  }

  std::vector<uint8_t> bytes_;
};

}  // namespace hylo::logs::detail
