// A rosbag2 sqlite3 database as a StorageSource. rosbag2 stores every message as one row of
// `messages` (id, topic_id, timestamp = receive time in ns, data = the CDR bytes), its topics in
// `topics` (id, name, type, serialization_format, ...), and indexes the rows by timestamp; rows
// are read in (timestamp, id) order, as rosbag2 plays them. A database cut short (disk full, a
// copy interrupted) is read in row order instead, the order the recorder inserted them, up to
// the first row that cannot be read.

#include <sqlite3.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>

#include "printable.h"
#include "storage_source.h"

namespace hylo::logs::detail {
namespace {

uint64_t BigEndian(const uint8_t* p, int bytes) {
  uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v = v << 8 | p[i];
  return v;
}

/// The database size its header announces, 0 when the header does not say (sqlite.org/fileformat:
/// page size at byte 16, page count at 28, valid when the change counter at 24 equals the
/// version-valid-for number at 92). Throws naming the file when it is no sqlite3 database.
uint64_t AnnouncedBytes(const std::string& path) {
  uint8_t header[100] = {};
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(header), sizeof(header)) ||
      std::memcmp(header, "SQLite format 3", 16) != 0) {
    throw std::runtime_error("sqlite3 database '" + path + "': not a sqlite3 database");
  }
  const uint64_t page_size = BigEndian(header + 16, 2) == 1 ? 65536 : BigEndian(header + 16, 2);
  const uint64_t pages = BigEndian(header + 28, 4);
  const bool valid = pages != 0 && BigEndian(header + 24, 4) == BigEndian(header + 92, 4);
  return valid ? page_size * pages : 0;
}

/// `path` as a sqlite URI (file:...?immutable=1): percent-encoded where the URI syntax needs it.
std::string ImmutableUri(const std::string& path) {
  std::string uri = "file:";
  for (const char c : std::filesystem::absolute(path).string()) {
    if (c == '%' || c == '?' || c == '#') {
      char hex[4];
      std::snprintf(hex, sizeof(hex), "%%%02X", static_cast<unsigned char>(c));
      uri += hex;
    } else {
      uri += c;
    }
  }
  return uri + "?immutable=1";
}

class SqliteSource : public StorageSource {
 public:
  explicit SqliteSource(const std::string& path) : path_(path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
      throw std::runtime_error("sqlite3 database '" + path + "': no such file");
    }
    file_bytes_ = std::filesystem::file_size(path, ec);
    const uint64_t announced = AnnouncedBytes(path);
    // Read-only and immutable: no lock, no journal, nothing written beside a recording that may
    // sit on a read-only disk.
    sqlite3* db = nullptr;
    const int rc = sqlite3_open_v2(ImmutableUri(path).c_str(), &db,
                                   SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr);
    db_.reset(db);
    if (rc != SQLITE_OK) Fail(std::string("cannot be opened (") + sqlite3_errstr(rc) + ")");
    if (announced > file_bytes_) {
      // sqlite refuses a file shorter than its header announces unless told to read what is
      // there; the pages past the end then read as corrupt, where reading stops.
      sqlite3_exec(db_.get(), "PRAGMA writable_schema = ON", nullptr, nullptr, nullptr);
      recovery_.emplace();
      recovery_->damage = "database cut short (" + std::to_string(file_bytes_) + " of " +
                          std::to_string(announced) + " bytes)";
      recovery_->file_bytes = file_bytes_;
    }
    ReadTopics();
    Prepare();
  }

  bool Next(StorageMessage* message) override {
    if (done_) return false;
    const int rc = sqlite3_step(statement_.get());
    if (rc == SQLITE_DONE) return End();
    if (rc != SQLITE_ROW) return Damaged(sqlite3_errmsg(db_.get()));
    const auto topic = topics_.find(sqlite3_column_int64(statement_.get(), 0));
    if (topic == topics_.end()) {
      if (recovery_) return Damaged("a row that cannot be read (its topic id is unknown)");
      Fail("a message of a topic id the topics table lacks");
    }
    message->topic = &topic->second;
    message->log_time_ns = sqlite3_column_int64(statement_.get(), 1);
    message->data = static_cast<const uint8_t*>(sqlite3_column_blob(statement_.get(), 2));
    message->size = static_cast<std::size_t>(sqlite3_column_bytes(statement_.get(), 2));
    if (recovery_) {
      if (recovery_->messages++ == 0) recovery_->first_receive_ns = message->log_time_ns;
      recovery_->last_receive_ns = message->log_time_ns;
    }
    return true;
  }

  std::vector<StorageTopic> Topics() const override {
    std::vector<StorageTopic> topics;
    for (const auto& [id, t] : topics_) topics.push_back(t);
    return topics;
  }
  bool topics_complete() const override { return true; }
  const LogRecovery* recovery() const override { return recovery_ ? &*recovery_ : nullptr; }
  const std::string& path() const override { return path_; }
  uint64_t file_bytes() const override { return file_bytes_; }

  bool IndexedStatistics(std::map<std::string, TopicStatistics>* stats) override {
    if (recovery_) return false;
    sqlite3_stmt* raw = nullptr;
    sqlite3_prepare_v2(db_.get(),
                       "SELECT topic_id, COUNT(*), MIN(timestamp), MAX(timestamp) FROM messages "
                       "GROUP BY topic_id",
                       -1, &raw, nullptr);
    std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)> s(raw, &sqlite3_finalize);
    std::map<std::string, TopicStatistics> found;
    for (const auto& [id, t] : topics_) found[t.name].type = t.type;
    int rc = SQLITE_ERROR;
    while (s && (rc = sqlite3_step(s.get())) == SQLITE_ROW) {
      const auto topic = topics_.find(sqlite3_column_int64(s.get(), 0));
      if (topic == topics_.end()) return false;
      TopicStatistics& t = found[topic->second.name];
      t.count += static_cast<uint64_t>(sqlite3_column_int64(s.get(), 1));
      t.first_ns = std::min<int64_t>(t.first_ns, sqlite3_column_int64(s.get(), 2));
      t.last_ns = std::max<int64_t>(t.last_ns, sqlite3_column_int64(s.get(), 3));
    }
    if (rc != SQLITE_DONE) return false;
    MergeStatistics(found, stats);
    return true;
  }

 private:
  [[noreturn]] void Fail(const std::string& why) const {
    throw std::runtime_error("sqlite3 database '" + path_ + "': " + Printable(why));
  }

  void ReadTopics() {
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db_.get(), "SELECT id, name, type, serialization_format FROM topics", -1,
                           &s, nullptr) != SQLITE_OK) {
      const std::string why = sqlite3_errmsg(db_.get());
      sqlite3_finalize(s);
      Fail("not a rosbag2 database (" + why + ")");
    }
    int rc;
    while ((rc = sqlite3_step(s)) == SQLITE_ROW) {
      const auto text = [&](int column) {
        const unsigned char* t = sqlite3_column_text(s, column);
        return t == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(t));
      };
      topics_[sqlite3_column_int64(s, 0)] = {text(1), text(2), text(3)};
    }
    const std::string why = sqlite3_errmsg(db_.get());
    sqlite3_finalize(s);
    if (rc != SQLITE_DONE) Fail("its topics cannot be read (" + why + ")");
  }

  bool HasTimestampIndex() {
    sqlite3_stmt* s = nullptr;
    bool found = false;
    if (sqlite3_prepare_v2(db_.get(),
                           "SELECT 1 FROM sqlite_master WHERE type = 'index' AND "
                           "tbl_name = 'messages' AND sql LIKE '%timestamp%'",
                           -1, &s, nullptr) == SQLITE_OK) {
      found = sqlite3_step(s) == SQLITE_ROW;
    }
    sqlite3_finalize(s);
    return found;
  }

  void Prepare() {
    // Without the timestamp index (or in a cut database, whose index may lie past the cut),
    // row order: the order the recorder inserted, which is receive order.
    const bool by_time = !recovery_ && HasTimestampIndex();
    const char* sql = by_time
                          ? "SELECT topic_id, timestamp, data FROM messages ORDER BY timestamp, id"
                          : "SELECT topic_id, timestamp, data FROM messages ORDER BY id";
    sqlite3_stmt* statement = nullptr;
    const int rc = sqlite3_prepare_v2(db_.get(), sql, -1, &statement, nullptr);
    statement_.reset(statement);
    if (rc != SQLITE_OK) {
      if (!recovery_)
        Fail(std::string("not a rosbag2 database (") + sqlite3_errmsg(db_.get()) + ")");
      Damaged(sqlite3_errmsg(db_.get()));
    }
  }

  bool End() {
    done_ = true;
    return false;
  }

  /// Reading stops at the first row sqlite cannot read: what came before is kept.
  bool Damaged(const std::string& why) {
    if (!recovery_) {
      recovery_.emplace();
      recovery_->damage = "database damaged";
      recovery_->file_bytes = file_bytes_;
    }
    recovery_->stop_reason = "sqlite: " + Printable(why);
    return End();
  }

  std::string path_;
  uint64_t file_bytes_ = 0;
  std::unique_ptr<sqlite3, decltype(&sqlite3_close)> db_{nullptr, &sqlite3_close};
  // After db_: finalized before the database closes.
  std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)> statement_{nullptr, &sqlite3_finalize};
  std::map<int64_t, StorageTopic> topics_;
  std::optional<LogRecovery> recovery_;
  bool done_ = false;
};

}  // namespace

std::unique_ptr<StorageSource> OpenSqliteSource(const std::string& path) {
  return std::make_unique<SqliteSource>(path);
}

}  // namespace hylo::logs::detail
