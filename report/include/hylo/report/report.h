#pragma once
// report.md: what a run did and how each back-end fared, for a person. The Table I figures,
// the plots (or why one is missing), the costmap image, the run's parameters and where each
// output file is. Paths are written relative to the report, so the folder can be moved.

#include <string>
#include <utility>
#include <vector>

#include "hylo/report/backend_table.h"
#include "hylo/report/plots.h"

namespace hylo::report {

/// An output of the run, listed in the report.
struct OutputFile {
  std::string what;  ///< one line: what the file holds
  std::string path;  ///< where it is
};

/// A section with one image and its caption, after the costmap (e.g. the inspection plan).
struct ImageSection {
  std::string title;    ///< its heading
  std::string text;     ///< a paragraph before the image (Markdown)
  std::string image;    ///< PNG path; empty = none
  std::string caption;  ///< a paragraph after it
};

struct ReportContent {
  std::string title;             ///< first heading
  std::string summary;           ///< a paragraph under the title (Markdown)
  std::vector<BackendRow> rows;  ///< the table, one row per back-end
  std::string table_caption;     ///< one paragraph under the table: what was measured
  std::vector<PlotFile> plots;   ///< figures, in order
  std::string costmap_png;       ///< the costmap image; empty = none
  std::string costmap_caption;   ///< its legend
  std::vector<ImageSection> sections;                           ///< after the costmap, in order
  std::vector<std::pair<std::string, std::string>> parameters;  ///< name, value (with unit)
  std::vector<OutputFile> files;                                ///< the run's outputs
};

/// The report as Markdown; paths are made relative to `report_dir`.
std::string RenderMarkdown(const ReportContent& content, const std::string& report_dir);

/// Writes RenderMarkdown to `path` (its folder is the report_dir). Throws std::runtime_error
/// naming the file when it cannot be written.
void WriteReport(const std::string& path, const ReportContent& content);

}  // namespace hylo::report
