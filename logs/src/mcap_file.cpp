// An MCAP file's ends: the leading magic, and the Footer with the summary it points to.

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "mcap_reader.h"

namespace hylo::logs::detail {
namespace {

// A summary repeats the schemas and channels and indexes every chunk: kilobytes to a few
// megabytes. One announcing more is corrupt data.
constexpr uint64_t kMaxSummaryBytes = uint64_t{1} << 30;

/// The summary's records, grouped by opcode as written; false when one is cut or corrupt.
bool ParseSummary(const std::vector<uint8_t>& bytes, McapSummary* summary) {
  std::size_t pos = 0;
  try {
    while (pos < bytes.size()) {
      if (bytes.size() - pos < kMcapRecordPrefix) return false;
      const uint8_t op = bytes[pos];
      const uint64_t length = LoadLe(&bytes[pos + 1], 8);
      if (length > bytes.size() - pos - kMcapRecordPrefix) return false;
      const uint8_t* content = &bytes[pos + kMcapRecordPrefix];
      if (op == kMcapSchema) {
        McapSchema s = ParseMcapSchema(content, length);
        if (s.id != 0) summary->schemas[s.id] = std::move(s);
      } else if (op == kMcapChannel) {
        McapChannel c = ParseMcapChannel(content, length);
        summary->channels[c.id] = std::move(c);
      } else if (op == kMcapChunkIndex) {
        summary->chunks.push_back(ParseMcapChunkIndex(content, length));
      } else if (op == kMcapStatistics) {
        summary->statistics = ParseMcapStatistics(content, length);
      }
      pos += kMcapRecordPrefix + length;
    }
  } catch (const McapError&) {
    return false;
  }
  return true;
}

}  // namespace

McapFile::McapFile(const std::string& path) : path_(path), in_(path, std::ios::binary) {
  std::error_code ec;
  size_ = std::filesystem::file_size(path, ec);
  if (!in_ || ec) throw std::runtime_error("MCAP file '" + path + "': cannot be opened");
  uint8_t magic[kMcapMagicBytes];
  if (!ReadAt(0, magic, sizeof(magic)) || std::memcmp(magic, kMcapMagic, sizeof(magic)) != 0) {
    throw std::runtime_error("MCAP file '" + path + "': not an MCAP file (no magic)");
  }
}

bool McapFile::ReadAt(uint64_t offset, void* out, uint64_t n) {
  if (offset > size_ || n > size_ - offset) return false;
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(offset));
  return static_cast<bool>(in_.read(static_cast<char*>(out), static_cast<std::streamsize>(n)));
}

McapEnd ReadMcapSummary(McapFile* file, McapSummary* summary, std::string* damage) {
  *summary = McapSummary();
  constexpr uint64_t kTail = kMcapRecordPrefix + kMcapFooterContent + kMcapMagicBytes;
  uint8_t tail[kTail];
  const uint64_t size = file->size();
  if (size < kMcapMagicBytes + kTail || !file->ReadAt(size - kTail, tail, kTail) ||
      tail[0] != kMcapFooter || LoadLe(tail + 1, 8) != kMcapFooterContent ||
      std::memcmp(tail + kTail - kMcapMagicBytes, kMcapMagic, kMcapMagicBytes) != 0) {
    *damage = "no footer (recording interrupted?)";
    return McapEnd::kDamaged;
  }
  const uint64_t footer_at = size - kTail;
  const McapFooter footer = ParseMcapFooter(tail + kMcapRecordPrefix, kMcapFooterContent);
  if (footer.summary_start == 0) return McapEnd::kNoSummary;
  const uint64_t end = footer.summary_offset_start != 0 ? footer.summary_offset_start : footer_at;
  if (footer.summary_start < kMcapMagicBytes || end < footer.summary_start || end > footer_at ||
      footer_at - footer.summary_start > kMaxSummaryBytes) {
    *damage = "the footer points outside the file (summary unreadable)";
    return McapEnd::kDamaged;
  }
  // The CRC covers the summary, the summary offsets and the footer up to its CRC field.
  std::vector<uint8_t> bytes(footer_at + kMcapRecordPrefix + 16 - footer.summary_start);
  if (!file->ReadAt(footer.summary_start, bytes.data(), bytes.size())) {
    *damage = "the summary cannot be read";
    return McapEnd::kDamaged;
  }
  if (footer.summary_crc != 0 && Crc32(bytes.data(), bytes.size()) != footer.summary_crc) {
    *damage = "the summary's CRC does not match (summary unreadable)";
    return McapEnd::kDamaged;
  }
  bytes.resize(end - footer.summary_start);
  if (!ParseSummary(bytes, summary)) {
    *damage = "a summary record is corrupt (summary unreadable)";
    return McapEnd::kDamaged;
  }
  for (const McapChunkIndex& c : summary->chunks) {
    if (c.chunk_start_offset < kMcapMagicBytes || c.chunk_length < kMcapRecordPrefix ||
        c.chunk_length > footer.summary_start - c.chunk_start_offset) {
      *damage = "a chunk index points outside the data section (summary unreadable)";
      return McapEnd::kDamaged;
    }
  }
  // Messages written outside chunks are not indexed: such files are read record by record.
  if (summary->chunks.empty() && summary->statistics && summary->statistics->message_count > 0) {
    return McapEnd::kNoSummary;
  }
  return McapEnd::kSummary;
}

bool ReadMcapMessageIndexes(McapFile* file, const std::vector<McapChunkIndex>& chunks,
                            std::map<uint16_t, McapChannelTimes>* times) {
  std::vector<uint8_t> bytes;
  for (const McapChunkIndex& c : chunks) {
    if (c.message_index_offsets.empty() || c.message_index_length > kMaxSummaryBytes) return false;
    bytes.resize(c.message_index_length);
    if (!file->ReadAt(c.chunk_start_offset + c.chunk_length, bytes.data(), bytes.size())) {
      return false;
    }
    try {
      for (std::size_t pos = 0; pos < bytes.size();) {
        if (bytes.size() - pos < kMcapRecordPrefix) return false;
        const uint64_t n = LoadLe(&bytes[pos + 1], 8);
        if (n > bytes.size() - pos - kMcapRecordPrefix) return false;
        if (bytes[pos] == kMcapMessageIndex) {
          McapFields f(&bytes[pos + kMcapRecordPrefix], n);
          McapChannelTimes& t = (*times)[f.U16()];
          const auto [entries, length] = f.Bytes(f.U32());
          McapFields list(entries, length);
          while (list.remaining() > 0) {
            const uint64_t time = list.U64();
            list.U64();  // the message's offset in the chunk
            ++t.count;
            t.first = std::min(t.first, time);
            t.last = std::max(t.last, time);
          }
        }
        pos += kMcapRecordPrefix + n;
      }
    } catch (const McapError&) {
      return false;
    }
  }
  return true;
}

std::string McapSchemaName(const std::map<uint16_t, McapSchema>& schemas, const McapChannel& c) {
  const auto it = schemas.find(c.schema_id);
  return it == schemas.end() ? std::string() : it->second.name;
}

}  // namespace hylo::logs::detail
