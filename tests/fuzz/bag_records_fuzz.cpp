// Fuzz target: a whole file as a ROS bag v2.0 read record by record, as hylo reads a bag whose
// index rosbag cannot read (recording killed, file cut short): the record walker
// (BagRecordScanner: records, chunks decompressed none/bz2/lz4, connections, messages, a cut
// tail), then the reader built on it, which yields scans of /points and IMU samples of /imu.
// The index path (rosbag_storage) is not fuzzed here: it is rosbag's own code.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "bag_records.h"
#include "bag_recovered_reader.h"
#include "fuzz_support.h"
#include "log_reader_fuzz.h"
#include "hylo/logs/log_reader.h"

namespace {

using hylo::fuzz::Require;
namespace logs = hylo::logs;
namespace detail = hylo::logs::detail;

volatile uint32_t g_sink = 0;  // keeps the message reads below

// What the walker promises: every message it yields has a known connection and a non-negative
// receive time, its bytes can be read, and what it calls readable lies inside the file.
void WalkRecords(const std::string& path) {
  detail::BagRecordScanner scanner(path);
  detail::BagMessageRecord record;
  uint32_t checksum = 0;
  while (scanner.Next(&record)) {
    Require(record.connection != nullptr, "a message without its connection");
    bool known = false;
    for (const auto& [id, c] : scanner.connections()) known = known || &c == record.connection;
    Require(known, "a message whose connection is not among the connections");
    Require(record.receive_ns >= 0, "a negative receive time");
    Require(record.size == 0 || record.data != nullptr, "message bytes missing");
    // Read every byte, so that ASan sees a message that points outside its chunk.
    for (uint32_t i = 0; i < record.size; ++i) checksum += record.data[i];
    Require(scanner.readable_bytes() <= scanner.file_bytes(), "readable past the file's end");
  }
  Require(scanner.readable_bytes() <= scanner.file_bytes(), "readable past the file's end");
  Require(!scanner.stop_reason().empty() || scanner.readable_bytes() == scanner.file_bytes(),
          "a clean end before the end of the file");
  Require(scanner.stop_reason().find('\n') == std::string::npos, "stop reason spans lines");
  g_sink = checksum;
}

// What a LogReader promises about the scans and samples it yields.
void ReadMessages(const std::string& path) {
  logs::LogReadOptions options;  // /points and /imu, the convention detected
  auto reader = detail::OpenRecoveredBag(path, options, "fuzzed");
  hylo::fuzz::CheckLogMessages(*reader);
  const logs::LogRecovery* recovery = reader->recovery();
  Require(recovery != nullptr, "the record-by-record reader reports no recovery");
  Require(recovery->unreadable_bytes <= recovery->file_bytes, "more unreadable bytes than bytes");
  const logs::LogReadCounters& counters = reader->counters();
  Require(counters.imu_messages + counters.scan_messages <= recovery->messages,
          "more messages delivered than found");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string path = hylo::fuzz::WriteScratchFile("input.bag", data, size);
  try {
    WalkRecords(path);
  } catch (const std::runtime_error& e) {
    hylo::fuzz::RequireClearError(e, path);  // cannot be opened / no version line
  }
  try {
    ReadMessages(path);
  } catch (const std::runtime_error& e) {
    hylo::fuzz::RequireClearError(e, path);
  }
  return 0;
}
