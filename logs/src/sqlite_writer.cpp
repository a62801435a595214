#include "sqlite_writer.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace hylo::logs::detail {

SqliteWriter::SqliteWriter(const std::string& path)
    : path_(path), temporary_(path + ".tmp" + std::to_string(::getpid())) {
  std::error_code ec;
  std::filesystem::remove(temporary_, ec);
  sqlite3* db = nullptr;
  const int rc =
      sqlite3_open_v2(temporary_.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
  db_.reset(db);
  if (rc != SQLITE_OK) Fail("cannot be created");
  // No journal: the database is a temporary until Close() renames it, so a crash mid-way leaves
  // nothing a reader would take for a recording; one transaction for all the rows.
  Execute("PRAGMA journal_mode = OFF");
  Execute("PRAGMA synchronous = OFF");
  Execute(
      "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY,ros_distro TEXT NOT NULL);"
      "CREATE TABLE metadata(id INTEGER PRIMARY KEY,metadata_version INTEGER NOT NULL,"
      "metadata TEXT NOT NULL);"
      "CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT NULL,"
      "serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL);"
      "CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL,"
      "timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
      "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
      // The layout is Humble's (schema 3, metadata 5), which every later rosbag2 reads.
      "INSERT INTO schema VALUES (3, 'humble');"
      "BEGIN TRANSACTION;");
  sqlite3_stmt* insert = nullptr;
  if (sqlite3_prepare_v2(db_.get(),
                         "INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)", -1,
                         &insert, nullptr) != SQLITE_OK) {
    Fail("cannot prepare its inserts");
  }
  insert_.reset(insert);
}

SqliteWriter::~SqliteWriter() {
  if (closed_) return;
  insert_.reset();
  db_.reset();
  std::error_code ec;
  std::filesystem::remove(temporary_, ec);
}

void SqliteWriter::Fail(const std::string& what) const {
  const std::string why = db_ ? sqlite3_errmsg(db_.get()) : "no database";
  throw std::runtime_error("sqlite3 database '" + path_ + "': " + what + " (" + why + ")");
}

void SqliteWriter::Execute(const std::string& sql) {
  char* error = nullptr;
  if (sqlite3_exec(db_.get(), sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string why = error != nullptr ? error : "unknown";
    sqlite3_free(error);
    throw std::runtime_error("sqlite3 database '" + path_ + "': " + why);
  }
}

int64_t SqliteWriter::AddTopic(const std::string& name, const std::string& type,
                               const std::string& format, const std::string& offered_qos_profiles) {
  sqlite3_stmt* raw = nullptr;
  sqlite3_prepare_v2(db_.get(),
                     "INSERT INTO topics (id, name, type, serialization_format, "
                     "offered_qos_profiles) VALUES (?, ?, ?, ?, ?)",
                     -1, &raw, nullptr);
  std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)> s(raw, &sqlite3_finalize);
  const int64_t id = ++topics_;
  const std::string* texts[] = {&name, &type, &format, &offered_qos_profiles};
  bool ok = s != nullptr && sqlite3_bind_int64(s.get(), 1, id) == SQLITE_OK;
  for (int i = 0; i < 4 && ok; ++i) {
    ok = sqlite3_bind_text(s.get(), i + 2, texts[i]->c_str(), static_cast<int>(texts[i]->size()),
                           SQLITE_TRANSIENT) == SQLITE_OK;
  }
  if (!ok || sqlite3_step(s.get()) != SQLITE_DONE) Fail("cannot add topic '" + name + "'");
  return id;
}

void SqliteWriter::Write(int64_t topic_id, int64_t timestamp_ns, const uint8_t* data,
                         std::size_t size) {
  if (closed_) throw std::logic_error("sqlite3 database '" + path_ + "': write after Close()");
  sqlite3_stmt* s = insert_.get();
  // SQLITE_STATIC: the bytes outlive the step below.
  if (sqlite3_bind_int64(s, 1, topic_id) != SQLITE_OK ||
      sqlite3_bind_int64(s, 2, timestamp_ns) != SQLITE_OK ||
      sqlite3_bind_blob64(s, 3, data, size, SQLITE_STATIC) != SQLITE_OK ||
      sqlite3_step(s) != SQLITE_DONE) {
    Fail("cannot store a message");
  }
  sqlite3_reset(s);
}

void SqliteWriter::Close(int metadata_version, const std::string& metadata_yaml) {
  if (closed_) return;
  sqlite3_stmt* raw = nullptr;
  sqlite3_prepare_v2(db_.get(), "INSERT INTO metadata (metadata_version, metadata) VALUES (?, ?)",
                     -1, &raw, nullptr);
  std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)> s(raw, &sqlite3_finalize);
  if (s == nullptr || sqlite3_bind_int(s.get(), 1, metadata_version) != SQLITE_OK ||
      sqlite3_bind_text(s.get(), 2, metadata_yaml.c_str(), static_cast<int>(metadata_yaml.size()),
                        SQLITE_TRANSIENT) != SQLITE_OK ||
      sqlite3_step(s.get()) != SQLITE_DONE) {
    Fail("cannot store its metadata");
  }
  s.reset();
  Execute("COMMIT;");
  insert_.reset();
  if (sqlite3_close(db_.release()) != SQLITE_OK) Fail("cannot be closed");
  std::error_code ec;
  std::filesystem::rename(temporary_, path_, ec);
  if (ec) {
    std::filesystem::remove(temporary_, ec);
    throw std::runtime_error("sqlite3 database '" + path_ + "': cannot be moved into place");
  }
  closed_ = true;
}

}  // namespace hylo::logs::detail
