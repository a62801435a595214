// report.md from a ReportContent: headings, the table, figures (or why each is missing),
// image sections, parameters and files.
#include "hylo/report/report.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "hylo/io/atomic_file.h"

namespace hylo::report {
namespace {

namespace fs = std::filesystem;

std::string Relative(const std::string& path, const std::string& report_dir) {
  if (path.empty()) return path;
  const fs::path relative = fs::path(path).lexically_relative(fs::path(report_dir));
  return relative.empty() || relative.string().rfind("..", 0) == 0 ? path : relative.string();
}

// Markdown image links break on spaces: angle brackets keep such paths whole.
std::string Link(const std::string& path) {
  return path.find(' ') == std::string::npos ? path : "<" + path + ">";
}

void WriteFigures(const ReportContent& c, const std::string& dir, std::ostringstream* md) {
  if (c.plots.empty()) return;
  *md << "## Figures\n\n";
  for (const PlotFile& plot : c.plots) {
    *md << "### " << plot.title << "\n\n";
    if (plot.ok) {
      *md << "![" << plot.title << "](" << Link(Relative(plot.path, dir)) << ")\n\n";
    } else {
      *md << "*Plot missing (`" << Relative(plot.path, dir) << "`): " << plot.message << "*\n\n";
    }
  }
}

void WriteCostmap(const ReportContent& c, const std::string& dir, std::ostringstream* md) {
  if (c.costmap_png.empty()) return;
  *md << "## Traversability costmap\n\n";
  if (fs::exists(c.costmap_png)) {
    *md << "![costmap](" << Link(Relative(c.costmap_png, dir)) << ")\n\n";
  } else {
    *md << "*Costmap image missing: `" << c.costmap_png << "` was not written.*\n\n";
  }
  if (!c.costmap_caption.empty()) *md << c.costmap_caption << "\n\n";
}

void WriteSections(const ReportContent& c, const std::string& dir, std::ostringstream* md) {
  for (const ImageSection& s : c.sections) {
    *md << "## " << s.title << "\n\n";
    if (!s.text.empty()) *md << s.text << "\n\n";
    if (!s.image.empty() && fs::exists(s.image)) {
      *md << "![" << s.title << "](" << Link(Relative(s.image, dir)) << ")\n\n";
    } else if (!s.image.empty()) {
      *md << "*Image missing: `" << s.image << "` was not written.*\n\n";
    }
    if (!s.caption.empty()) *md << s.caption << "\n\n";
  }
}

void WriteParameters(const ReportContent& c, std::ostringstream* md) {
  if (c.parameters.empty()) return;
  *md << "## Parameters\n\n| parameter | value |\n|---|---|\n";
  for (const auto& [name, value] : c.parameters) *md << "| " << name << " | " << value << " |\n";
  *md << "\n";
}

void WriteFiles(const ReportContent& c, const std::string& dir, std::ostringstream* md) {
  if (c.files.empty()) return;
  *md << "## Files\n\n| file | holds |\n|---|---|\n";
  for (const OutputFile& f : c.files) {
    *md << "| `" << Relative(f.path, dir) << "` | " << f.what << " |\n";
  }
  *md << "\n";
}

}  // namespace

std::string RenderMarkdown(const ReportContent& content, const std::string& report_dir) {
  std::ostringstream md;
  md << "# " << content.title << "\n\n";
  if (!content.summary.empty()) md << content.summary << "\n\n";
  md << "## Results per back-end (cf. Table I of Alamanos et al.)\n\n"
     << FormatTable(content.rows, TableStyle::kMarkdown) << "\n";
  if (!content.table_caption.empty()) md << content.table_caption << "\n\n";
  WriteFigures(content, report_dir, &md);
  WriteCostmap(content, report_dir, &md);
  WriteSections(content, report_dir, &md);
  WriteParameters(content, &md);
  WriteFiles(content, report_dir, &md);
  return md.str();
}

void WriteReport(const std::string& path, const ReportContent& content) {
  const std::string dir = fs::path(path).parent_path().string();
  io::WriteFileAtomically(path, RenderMarkdown(content, dir.empty() ? "." : dir));
}

}  // namespace hylo::report
