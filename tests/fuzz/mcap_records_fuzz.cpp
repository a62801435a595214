// Fuzz target: a whole file as an MCAP recording, read every way hylo reads one: its ends (the
// Footer and the summary), the record-by-record walk a recording without summary gets (records,
// chunks decompressed stored/zstd/lz4, a cut tail), the indexed reader when the summary reads,
// the storage source on top, and the LogReader that yields scans of /points and IMU samples of
// /imu. The walker and readers are private to hylo_logs (logs/src).

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz_support.h"
#include "log_reader_fuzz.h"
#include "hylo/logs/rosbag2_reader.h"
#include "mcap_reader.h"
#include "storage_source.h"

namespace {

using hylo::fuzz::Require;
namespace logs = hylo::logs;
namespace detail = hylo::logs::detail;

volatile uint32_t g_sink = 0;  // keeps the message reads below

uint32_t Touch(const detail::McapMessage& m) {
  Require(m.channel != nullptr, "a message without its channel");
  Require(m.size == 0 || m.data != nullptr, "message bytes missing");
  uint32_t sum = 0;
  for (uint64_t i = 0; i < m.size; ++i) sum += m.data[i];  // ASan sees bytes out of the buffer
  return sum;
}

// What the walker promises: messages with a known channel whose bytes can be read, and a
// readable part inside the file.
void Walk(const std::string& path) {
  detail::McapLinearScanner scanner(path);
  detail::McapMessage m;
  uint32_t sum = 0;
  while (scanner.Next(&m)) {
    sum += Touch(m);
    bool known = false;
    for (const auto& [id, c] : scanner.channels()) known = known || &c == m.channel;
    Require(known, "a message whose channel is not among the channels");
  }
  Require(scanner.readable_bytes() <= scanner.file_bytes(), "readable past the file's end");
  Require(scanner.stop_reason().find('\n') == std::string::npos, "stop reason spans lines");
  g_sink = sum;
}

// Through the summary: log-time order.
void Indexed(const std::string& path) {
  detail::McapFile file(path);
  detail::McapSummary summary;
  std::string damage;
  if (detail::ReadMcapSummary(&file, &summary, &damage) != detail::McapEnd::kSummary) {
    Require(damage.find('\n') == std::string::npos, "damage spans lines");
    return;
  }
  detail::McapIndexedReader reader(path, std::move(summary));
  detail::McapMessage m;
  uint64_t last = 0;
  uint32_t sum = 0;
  while (reader.Next(&m)) {
    Require(m.log_time >= last, "indexed messages out of log-time order");
    last = m.log_time;
    sum += Touch(m);
  }
  g_sink = sum;
}

void Source(const std::string& path) {
  auto source = detail::OpenMcapSource(path);
  std::map<std::string, detail::TopicStatistics> stats;
  source->IndexedStatistics(&stats);
  detail::StorageMessage m;
  while (source->Next(&m)) Require(m.topic != nullptr, "a message without its topic");
  if (const logs::LogRecovery* r = source->recovery()) {
    Require(r->unreadable_bytes <= r->file_bytes, "more unreadable bytes than bytes");
  }
}

// What a LogReader promises about the scans and samples it yields.
void ReadMessages(const std::string& path) {
  auto reader = logs::OpenRosbag2(path, logs::LogReadOptions());
  hylo::fuzz::CheckLogMessages(*reader);
  if (const logs::LogRecovery* r = reader->recovery()) {
    Require(r->Summary().find('\n') == std::string::npos, "recovery summary spans lines");
  }
}

template <class Read>
void Expect(const std::string& path, Read read) {
  try {
    read(path);
  } catch (const std::runtime_error& e) {
    hylo::fuzz::RequireClearError(e, path);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string path = hylo::fuzz::WriteScratchFile("input.mcap", data, size);
  Expect(path, Walk);
  Expect(path, Indexed);
  Expect(path, Source);
  Expect(path, ReadMessages);
  return 0;
}
