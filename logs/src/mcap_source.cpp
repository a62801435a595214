// An MCAP file as a StorageSource: through its summary in log-time order, or, without one
// (a recording killed before it was written, a writer that writes none), record by record.

#include <algorithm>
#include <limits>
#include <map>
#include <optional>

#include "mcap_reader.h"
#include "storage_source.h"

namespace hylo::logs::detail {
namespace {

class McapSource : public StorageSource {
 public:
  explicit McapSource(const std::string& path) : path_(path) {
    McapFile file(path);
    file_bytes_ = file.size();
    McapSummary summary;
    std::string damage;
    const McapEnd end = ReadMcapSummary(&file, &summary, &damage);
    if (end == McapEnd::kSummary) {
      indexed_.emplace(path, std::move(summary));
      return;
    }
    linear_.emplace(path);
    if (end == McapEnd::kDamaged) {
      recovery_.emplace();
      recovery_->damage = damage;
      recovery_->file_bytes = file_bytes_;
    }
  }

  bool Next(StorageMessage* message) override {
    McapMessage m;
    if (!(indexed_ ? indexed_->Next(&m) : linear_->Next(&m))) return End();
    message->topic = &TopicOf(*m.channel);
    message->log_time_ns = ClampedNs(m.log_time);
    message->data = m.data;
    message->size = static_cast<std::size_t>(m.size);
    if (recovery_) {
      if (recovery_->messages++ == 0) recovery_->first_receive_ns = message->log_time_ns;
      recovery_->last_receive_ns = message->log_time_ns;
    }
    return true;
  }

  std::vector<StorageTopic> Topics() const override {
    std::vector<StorageTopic> topics;
    for (const auto& [id, c] : channels()) topics.push_back(Topic(c));
    return topics;
  }
  bool topics_complete() const override { return indexed_.has_value(); }
  const LogRecovery* recovery() const override { return recovery_ ? &*recovery_ : nullptr; }
  const std::string& path() const override { return path_; }
  uint64_t file_bytes() const override { return file_bytes_; }

  bool IndexedStatistics(std::map<std::string, TopicStatistics>* stats) override {
    if (!indexed_) return false;
    McapFile file(path_);
    std::map<uint16_t, McapChannelTimes> times;
    if (!ReadMcapMessageIndexes(&file, indexed_->summary().chunks, &times)) return false;
    std::map<std::string, TopicStatistics> found;
    for (const auto& [id, c] : channels()) {
      TopicStatistics& t = found[c.topic];
      t.type = McapSchemaName(schemas(), c);
      const auto it = times.find(id);
      if (it == times.end()) continue;
      t.count += it->second.count;
      t.first_ns = std::min(t.first_ns, ClampedNs(it->second.first));
      t.last_ns = std::max(t.last_ns, ClampedNs(it->second.last));
    }
    MergeStatistics(found, stats);
    return true;
  }

  std::set<std::string> ChunkCompressions() const override {
    if (!indexed_) return linear_->compressions();
    std::set<std::string> codecs;
    for (const McapChunkIndex& c : indexed_->summary().chunks) codecs.insert(c.compression);
    return codecs;
  }

 private:
  // Log times past int64 (never written by a recorder) are kept ordered at the end.
  static int64_t ClampedNs(uint64_t t) {
    return static_cast<int64_t>(std::min<uint64_t>(t, std::numeric_limits<int64_t>::max()));
  }

  const std::map<uint16_t, McapChannel>& channels() const {
    return indexed_ ? indexed_->channels() : linear_->channels();
  }
  const std::map<uint16_t, McapSchema>& schemas() const {
    return indexed_ ? indexed_->schemas() : linear_->schemas();
  }

  StorageTopic Topic(const McapChannel& c) const {
    return {c.topic, McapSchemaName(schemas(), c), c.message_encoding};
  }

  const StorageTopic& TopicOf(const McapChannel& c) {
    auto it = topics_.find(c.id);
    if (it == topics_.end()) it = topics_.emplace(c.id, Topic(c)).first;
    return it->second;
  }

  bool End() {
    if (linear_) {
      if (!linear_->stop_reason().empty() && !recovery_) {
        // A file with its footer but no summary, damaged inside: corrupt, as in an indexed file.
        throw std::runtime_error("MCAP file '" + path_ + "': " + linear_->stop_reason());
      }
      if (recovery_) {
        recovery_->stop_reason = linear_->stop_reason();
        recovery_->unreadable_bytes = file_bytes_ - linear_->readable_bytes();
      }
    }
    return false;
  }

  std::string path_;
  uint64_t file_bytes_ = 0;
  std::optional<McapIndexedReader> indexed_;
  std::optional<McapLinearScanner> linear_;
  std::map<uint16_t, StorageTopic> topics_;  // by channel id; pointers handed out stay valid
  std::optional<LogRecovery> recovery_;
};

}  // namespace

std::unique_ptr<StorageSource> OpenMcapSource(const std::string& path) {
  return std::make_unique<McapSource>(path);
}

}  // namespace hylo::logs::detail
