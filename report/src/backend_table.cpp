// The per-back-end table: one list of columns drives the terminal, Markdown and JSON forms,
// so the three never disagree on a header, a unit or a rounding.
#include "hylo/report/backend_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace hylo::report {
namespace {

struct Column {
  const char* header;          // what a reader sees, with the unit
  const char* json_key;        // key in the JSON form, with the unit
  double BackendRow::*figure;  // the value in a row
  int decimals;                // printed precision
};

// Table I of Alamanos et al. (c2c mean/std), plus the trajectory and cost figures.
const Column kColumns[] = {
    {"c2c mean [m]", "c2c_mean_m", &BackendRow::c2c_mean_m, 4},
    {"c2c std [m]", "c2c_std_m", &BackendRow::c2c_std_m, 4},
    {"ATE RMSE [m]", "ate_rmse_m", &BackendRow::ate_rmse_m, 4},
    {"live ATE [m]", "ate_live_rmse_m", &BackendRow::ate_live_rmse_m, 4},
    {"RPE RMSE [m]", "rpe_rmse_m", &BackendRow::rpe_rmse_m, 4},
    {"ms/scan median", "ms_per_scan_median", &BackendRow::ms_per_scan_median, 2},
    {"ms/scan p99", "ms_per_scan_p99", &BackendRow::ms_per_scan_p99, 2},
    {"CPU ms/scan", "cpu_ms_per_scan_median", &BackendRow::cpu_ms_per_scan_median, 2},
    {"peak mem [MiB]", "peak_memory_mb", &BackendRow::peak_memory_mb, 1},
    {"scans", "scans", &BackendRow::scans, 0},
};

// The cells of one row, backend name first.
std::vector<std::string> Cells(const BackendRow& row) {
  std::vector<std::string> cells{row.backend};
  for (const Column& c : kColumns) {
    cells.push_back(row.status == RowStatus::kOk ? FormatFigure(row.*(c.figure), c.decimals)
                                                 : ToString(row.status));
  }
  return cells;
}

std::vector<std::string> HeaderCells() {
  std::vector<std::string> cells{"back-end"};
  for (const Column& c : kColumns) cells.emplace_back(c.header);
  return cells;
}

std::string Pad(const std::string& text, std::size_t width, bool left) {
  const std::string fill(width > text.size() ? width - text.size() : 0, ' ');
  return left ? text + fill : fill + text;
}

std::string TerminalTable(const std::vector<std::vector<std::string>>& lines) {
  std::vector<std::size_t> widths(lines.front().size(), 0);
  for (const auto& line : lines) {
    for (std::size_t i = 0; i < line.size(); ++i) widths[i] = std::max(widths[i], line[i].size());
  }
  std::ostringstream out;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    for (std::size_t i = 0; i < lines[l].size(); ++i) {
      out << (i == 0 ? "" : "  ") << Pad(lines[l][i], widths[i], i == 0);
    }
    out << '\n';
    if (l == 0) {
      std::size_t total = 0;
      for (std::size_t w : widths) total += w + 2;
      out << std::string(total - 2, '-') << '\n';
    }
  }
  return out.str();
}

std::string MarkdownTable(const std::vector<std::vector<std::string>>& lines) {
  std::ostringstream out;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    out << '|';
    for (const std::string& cell : lines[l]) out << ' ' << cell << " |";
    out << '\n';
    if (l == 0) {
      out << "|---|";
      for (std::size_t i = 1; i < lines[l].size(); ++i) out << "---:|";
      out << '\n';
    }
  }
  return out.str();
}

}  // namespace

std::string ToString(RowStatus status) {
  switch (status) {
    case RowStatus::kOk:
      return "ok";
    case RowStatus::kFailed:
      return "failed";
  }
  return "?";
}

std::string FormatFigure(double value, int decimals) {
  if (!std::isfinite(value)) return "n/a";
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", std::max(decimals, 0), value);
  return text;
}

std::string FormatTable(const std::vector<BackendRow>& rows, TableStyle style) {
  std::vector<std::vector<std::string>> lines{HeaderCells()};
  for (const BackendRow& row : rows) lines.push_back(Cells(row));
  std::string text = style == TableStyle::kMarkdown ? MarkdownTable(lines) : TerminalTable(lines);
  std::string notes;
  for (const BackendRow& row : rows) {
    if (row.note.empty()) continue;
    notes += (style == TableStyle::kMarkdown ? "- " : "  ") + row.backend + " (" +
             ToString(row.status) + "): " + row.note + "\n";
  }
  if (!notes.empty()) text += (style == TableStyle::kMarkdown ? "\n" : "") + notes;
  return text;
}

io::Json TableToJson(const std::vector<BackendRow>& rows) {
  io::Json table = io::Json::array();
  for (const BackendRow& row : rows) {
    io::Json j = io::Json::object();
    j["backend"] = row.backend;
    j["status"] = ToString(row.status);
    j["note"] = row.note;
    for (const Column& c : kColumns) {
      const double value = row.*(c.figure);
      j[c.json_key] = std::isfinite(value) ? io::Json(value) : io::Json();
    }
    table.push_back(j);
  }
  return table;
}

}  // namespace hylo::report
