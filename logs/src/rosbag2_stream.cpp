// A rosbag2 path resolved into its storage files, and those files merged by log time.

#include "rosbag2_stream.h"

#include <unistd.h>
#include <zstd.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "mcap_chunk_codec.h"
#include "mcap_format.h"
#include "printable.h"

namespace hylo::logs::detail {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void Fail(const std::string& path, const std::string& why) {
  throw std::runtime_error("bag '" + path + "': " + Printable(why));
}

std::string StorageOfFile(const std::string& path) {
  char head[16] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(head, sizeof(head));
  if (std::memcmp(head, kMcapMagic, kMcapMagicBytes) == 0) return "mcap";
  if (std::memcmp(head, "SQLite format 3", 16) == 0) return "sqlite3";
  return "";
}

/// The split index rosbag2 appends to each file's stem (name_3.mcap -> 3), -1 when none.
long SplitIndex(const fs::path& file) {
  std::string stem = file.stem().string();
  const std::size_t underscore = stem.rfind('_');
  if (underscore == std::string::npos || underscore + 1 == stem.size()) return -1;
  const std::string digits = stem.substr(underscore + 1);
  if (digits.size() > 9 || !std::all_of(digits.begin(), digits.end(), ::isdigit)) return -1;
  return std::stol(digits);
}

/// The storage files of a directory without metadata.yaml, in split order.
void ListStorageFiles(Rosbag2Layout* layout) {
  std::vector<fs::path> mcap, db3;
  for (const auto& entry : fs::directory_iterator(layout->path)) {
    if (!entry.is_regular_file()) continue;
    const std::string ext = entry.path().extension().string();
    if (ext == ".mcap") mcap.push_back(entry.path());
    if (ext == ".db3") db3.push_back(entry.path());
  }
  if (mcap.empty() == db3.empty()) {
    Fail(layout->path, mcap.empty() ? "no metadata.yaml and no .db3 or .mcap file"
                                    : "no metadata.yaml, and both .db3 and .mcap files");
  }
  std::vector<fs::path>& files = mcap.empty() ? db3 : mcap;
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    const long ia = SplitIndex(a), ib = SplitIndex(b);
    return ia != ib ? ia < ib : a.filename() < b.filename();
  });
  layout->storage = mcap.empty() ? "sqlite3" : "mcap";
  for (const fs::path& f : files) layout->files.push_back(f.string());
  layout->damage = "no metadata.yaml (recording interrupted?)";
}

void FromMetadata(Rosbag2Layout* layout) {
  const std::string meta_path = (fs::path(layout->path) / kRosbag2MetadataFile).string();
  layout->metadata = ReadRosbag2Metadata(meta_path);
  const Rosbag2Metadata& m = *layout->metadata;
  layout->storage = m.storage_identifier;
  if (layout->storage != "sqlite3" && layout->storage != "mcap") {
    Fail(layout->path,
         "storage '" + m.storage_identifier + "' is not supported (hylo reads sqlite3 and mcap)");
  }
  if (!m.compression_format.empty()) {
    if (m.compression_format != "zstd") {
      Fail(layout->path, "compression '" + m.compression_format +
                             "' is not supported (hylo reads zstd; `ros2 bag convert` rewrites "
                             "a recording uncompressed)");
    }
    if (m.compression_mode != "file" && m.compression_mode != "message") {
      Fail(layout->path, "unknown compression mode '" + m.compression_mode + "' (file, message)");
    }
    layout->compression_mode = m.compression_mode;
  }
  if (m.relative_file_paths.empty()) Fail(layout->path, "metadata.yaml names no storage file");
  for (const std::string& relative : m.relative_file_paths) {
    const fs::path file = fs::path(layout->path) / relative;
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) {
      Fail(layout->path, "storage file '" + relative + "' (listed in metadata.yaml) is missing");
    }
    layout->files.push_back(file.string());
  }
}

/// `path`, one zstd stream, decompressed into a new temporary file; returns its path.
std::string DecompressFile(const std::string& bag, const std::string& path) {
  static std::atomic<int> counter{0};
  const fs::path out_path =
      fs::temp_directory_path() /
      ("hylo_rosbag2_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + "_" +
       fs::path(path).stem().filename().string());
  std::ifstream in(path, std::ios::binary);
  std::ofstream out(out_path, std::ios::binary);
  if (!in || !out) Fail(bag, "cannot decompress '" + path + "' to " + out_path.string());
  std::unique_ptr<ZSTD_DStream, decltype(&ZSTD_freeDStream)> stream(ZSTD_createDStream(),
                                                                    &ZSTD_freeDStream);
  ZSTD_initDStream(stream.get());
  std::vector<char> input(ZSTD_DStreamInSize()), output(ZSTD_DStreamOutSize());
  std::size_t last = 1;
  while (in.read(input.data(), static_cast<std::streamsize>(input.size())) || in.gcount() > 0) {
    ZSTD_inBuffer src{input.data(), static_cast<std::size_t>(in.gcount()), 0};
    while (src.pos < src.size) {
      ZSTD_outBuffer dst{output.data(), output.size(), 0};
      last = ZSTD_decompressStream(stream.get(), &dst, &src);
      if (ZSTD_isError(last)) {
        out.close();
        fs::remove(out_path);
        Fail(bag, "'" + path + "' is not a zstd stream (" + ZSTD_getErrorName(last) + ")");
      }
      out.write(output.data(), static_cast<std::streamsize>(dst.pos));
    }
  }
  if (last != 0 || !out) {
    out.close();
    fs::remove(out_path);
    Fail(bag, "'" + path + "': its zstd stream is cut short");
  }
  return out_path.string();
}

}  // namespace

std::pair<const uint8_t*, std::size_t> MessageBytes::Of(const StorageMessage& m) {
  if (!compressed_) return {m.data, m.size};
  const unsigned long long size = ZSTD_getFrameContentSize(m.data, m.size);
  std::string why = "not a zstd frame that states its size";
  if (size == ZSTD_CONTENTSIZE_ERROR || size == ZSTD_CONTENTSIZE_UNKNOWN ||
      !DecompressMcapChunk("zstd", m.data, m.size, size, true, &buffer_, &why)) {
    throw std::runtime_error("compressed message: " + why);
  }
  return {buffer_.data(), buffer_.size()};
}

bool HasRosbag2StorageMagic(const std::string& path) { return !StorageOfFile(path).empty(); }

Rosbag2Layout ResolveRosbag2(const std::string& path) {
  Rosbag2Layout layout;
  layout.path = path;
  std::error_code ec;
  if (!fs::exists(path, ec)) Fail(path, "does not exist");
  if (!fs::is_directory(path, ec)) {
    layout.storage = StorageOfFile(path);
    if (layout.storage.empty()) Fail(path, "neither an MCAP file nor a sqlite3 database");
    layout.files = {path};
    return layout;
  }
  if (fs::exists(fs::path(path) / kRosbag2MetadataFile, ec)) {
    FromMetadata(&layout);
  } else {
    ListStorageFiles(&layout);
  }
  return layout;
}

Rosbag2Stream::Rosbag2Stream(const Rosbag2Layout& layout) : layout_(layout) {
  try {
    for (const std::string& file : layout_.files) {
      std::string readable = file;
      if (layout_.compression_mode == "file") {
        readable = DecompressFile(layout_.path, file);
        temporaries_.push_back(readable);
      }
      sources_.push_back(layout_.storage == "mcap" ? OpenMcapSource(readable)
                                                   : OpenSqliteSource(readable));
    }
  } catch (...) {
    for (const std::string& t : temporaries_) fs::remove(t);
    throw;
  }
  heads_.resize(sources_.size());
  has_head_.assign(sources_.size(), false);
  recovery_.damage = layout_.damage;
}

Rosbag2Stream::~Rosbag2Stream() {
  sources_.clear();  // closed before their temporary files go
  std::error_code ec;
  for (const std::string& t : temporaries_) fs::remove(t, ec);
}

bool Rosbag2Stream::Next(StorageMessage* message) {
  if (!started_) {
    for (std::size_t i = 0; i < sources_.size(); ++i) has_head_[i] = sources_[i]->Next(&heads_[i]);
    started_ = true;
  } else if (last_ >= 0) {
    has_head_[last_] = sources_[last_]->Next(&heads_[last_]);
  }
  last_ = -1;
  for (std::size_t i = 0; i < sources_.size(); ++i) {
    if (has_head_[i] && (last_ < 0 || heads_[i].log_time_ns < heads_[last_].log_time_ns)) {
      last_ = static_cast<int>(i);
    }
  }
  if (last_ < 0) return false;
  *message = heads_[last_];
  if (messages_++ == 0) first_ns_ = message->log_time_ns;
  last_ns_ = message->log_time_ns;
  return true;
}

TopicTypes Rosbag2Stream::Topics() const {
  TopicTypes topics;
  const auto add = [&](const std::string& name, const std::string& type) {
    std::vector<std::string>& types = topics[name];
    if (std::find(types.begin(), types.end(), type) == types.end()) types.push_back(type);
  };
  if (layout_.metadata) {
    for (const Rosbag2TopicInfo& t : layout_.metadata->topics) add(t.name, t.type);
  }
  for (const auto& source : sources_) {
    for (const StorageTopic& t : source->Topics()) add(t.name, t.type);
  }
  return topics;
}

std::vector<StorageTopic> Rosbag2Stream::TopicEntries(const std::string& name) const {
  std::vector<StorageTopic> entries;
  if (layout_.metadata) {
    for (const Rosbag2TopicInfo& t : layout_.metadata->topics) {
      if (t.name == name) entries.push_back({t.name, t.type, t.serialization_format});
    }
  }
  for (const auto& source : sources_) {
    for (const StorageTopic& t : source->Topics()) {
      if (t.name == name) entries.push_back(t);
    }
  }
  return entries;
}

bool Rosbag2Stream::topics_complete() const {
  if (layout_.metadata) return true;
  for (const auto& source : sources_) {
    if (!source->topics_complete()) return false;
  }
  return true;
}

const LogRecovery* Rosbag2Stream::recovery() {
  LogRecovery r;
  r.damage = layout_.damage;
  bool damaged = !r.damage.empty();
  for (const auto& source : sources_) {
    r.file_bytes += source->file_bytes();
    const LogRecovery* s = source->recovery();
    if (s == nullptr) continue;
    damaged = true;
    const std::string name = fs::path(source->path()).filename().string();
    r.damage += (r.damage.empty() ? "" : "; ") + name + ": " + s->damage;
    if (!s->stop_reason.empty()) {
      r.stop_reason += (r.stop_reason.empty() ? "" : "; ") + name + ": " + s->stop_reason;
    }
    r.unreadable_bytes += s->unreadable_bytes;
  }
  if (!damaged) return nullptr;
  r.messages = messages_;
  r.first_receive_ns = first_ns_;
  r.last_receive_ns = last_ns_;
  recovery_ = r;
  return &recovery_;
}

}  // namespace hylo::logs::detail
