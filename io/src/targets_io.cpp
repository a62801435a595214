// Targets as CSV (reader and writer) and the reader chosen by extension; YAML is in
// targets_yaml.cpp.
#include "hylo/io/targets_io.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <vector>

#include "hylo/io/atomic_file.h"
#include "hylo/io/text.h"
#include "targets_fields.h"

namespace hylo::io {
namespace {

using targets::Key;

std::string Trim(const std::string& text) {
  const std::size_t begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find_last_not_of(" \t\r") - begin + 1);
}

std::vector<std::string> SplitCells(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = line.find(',', begin);
    cells.push_back(Trim(line.substr(begin, comma - begin)));
    if (comma == std::string::npos) return cells;
    begin = comma + 1;
  }
}

std::string At(int line, std::size_t column, Key key) {
  return "line " + std::to_string(line) + ", column " + std::to_string(column + 1) + " (" +
         targets::NameOf(key) + ")";
}

// The header's columns, each a known key once.
std::vector<Key> ParseHeader(const std::string& path, int line, const std::vector<std::string>& cells) {
  std::vector<Key> columns;
  std::set<Key> seen;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    Key key;
    const std::string where = "line " + std::to_string(line) + ", column " + std::to_string(c + 1);
    if (!targets::KeyOf(ToLower(cells[c]), &key)) {
      ThrowFileError(path, where + ": unknown column '" + targets::Printable(cells[c]) +
                               "' (the header names columns among: " + targets::KeyNames() + ")");
    }
    if (!seen.insert(key).second)
      ThrowFileError(path, where + ": column '" + targets::Printable(cells[c]) + "' given twice");
    columns.push_back(key);
  }
  for (const Key k : {Key::kId, Key::kX, Key::kY, Key::kZ}) {
    if (!seen.count(k)) {
      ThrowFileError(path, "line " + std::to_string(line) + ": the header has no column '" +
                               targets::NameOf(k) + "' (id, x, y, z are required)");
    }
  }
  return columns;
}

std::string FormatCell(double value) {
  if (std::isnan(value)) return "";
  char text[32];
  std::snprintf(text, sizeof(text), "%.6f", value);
  return text;
}

}  // namespace

bool IsValidTargetId(const std::string& id) {
  if (id.empty() || id.size() > 64) return false;
  const auto allowed = [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '-' || c == '.';
  };
  if (!std::isalnum(static_cast<unsigned char>(id[0])) && id[0] != '_') return false;
  for (const char c : id) {
    if (!allowed(static_cast<unsigned char>(c))) return false;
  }
  return true;
}

std::vector<inspection::Target> ReadTargetsCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) ThrowFileError(path, "cannot open (missing or unreadable)");
  std::vector<inspection::Target> out;
  std::vector<Key> columns;
  std::map<std::string, std::string> first_seen;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (line == 1 && text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);  // a UTF-8 mark
    const std::string trimmed = Trim(text);
    if (trimmed.empty() || trimmed[0] == '#') continue;
    const std::vector<std::string> cells = SplitCells(trimmed);
    if (columns.empty()) {
      columns = ParseHeader(path, line, cells);
      continue;
    }
    if (cells.size() != columns.size()) {
      ThrowFileError(path, "line " + std::to_string(line) + ": expected " +
                               std::to_string(columns.size()) + " comma-separated values (as the "
                               "header), found " + std::to_string(cells.size()));
    }
    inspection::Target target;
    std::set<Key> given;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (cells[c].empty()) continue;  // the default
      given.insert(columns[c]);
      if (columns[c] == Key::kId) {
        target.id = cells[c];
        continue;
      }
      double value;
      if (!targets::ParseFinite(cells[c], &value)) {
        ThrowFileError(path, At(line, c, columns[c]) + ": '" + targets::Printable(cells[c]) +
                                 "' is not a finite number");
      }
      targets::Assign(columns[c], value, &target);
    }
    targets::Finish(path, "line " + std::to_string(line), given, target, &first_seen);
    out.push_back(target);
  }
  if (columns.empty()) ThrowFileError(path, "no header line (id,x,y,z,...)");
  if (out.empty()) ThrowFileError(path, "no target after the header");
  return out;
}

std::vector<inspection::Target> ReadTargets(const std::string& path) {
  const std::string ext = ToLower(std::filesystem::path(path).extension().string());
  if (ext == ".csv") return ReadTargetsCsv(path);
  if (ext == ".yaml" || ext == ".yml") return ReadTargetsYaml(path);
  ThrowFileError(path, "unknown targets format '" + ext + "' (expected .csv, .yaml or .yml)");
}

void WriteTargetsCsv(const std::string& path, const std::vector<inspection::Target>& targets) {
  std::string text =
      "id,x,y,z,min_range_m,max_range_m,size_x,size_y,size_z,view_azimuth_deg,"
      "view_tolerance_deg\n";
  for (const inspection::Target& t : targets) {
    const bool box = t.IsBox();
    const double nan = std::nan("");
    text += t.id;
    for (const double v :
         {t.position.x(), t.position.y(), t.position.z(), t.min_range_m, t.max_range_m,
          box ? t.box_size_m.x() : nan, box ? t.box_size_m.y() : nan, box ? t.box_size_m.z() : nan,
          t.view_azimuth_deg, t.view_tolerance_deg}) {
      text += "," + FormatCell(v);
    }
    text += "\n";
  }
  WriteFileAtomically(path, text);
}

}  // namespace hylo::io
