#include "hylo/config/config_doc.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <sstream>
#include <type_traits>
#include <vector>

#include "enum_fields.h"
#include "hylo/common/check.h"
#include "run_config_fields.h"
#include "yaml_visitors.h"

namespace hylo::config {
namespace {

// The text above the tables: how a user gets a configuration and what the reader checks.
constexpr const char* kIntro = R"(# Configuration reference

<!-- Generated from the field list (config/src/run_config_fields.h) by `hylo config --doc`;
     do not edit by hand. After changing a field or its description, regenerate it:
       build/apps/hylo config --doc --out docs/configuration.md
     (the test ConfigurationDoc.CommittedFileIsCurrent fails until then). -->

One YAML file configures a run: `hylo map`, `hylo localize`, `hylo compare` and `hylo demo`
take it as `--config FILE`, the ROS node as its `config` parameter.

- **Start from a preset.** `config/presets/` holds one file per sensor set-up (Velodyne
  VLP-16, Robosense RS-16, Ouster OS1, Hesai XT32, Livox, a hand-held lidar without IMU, the
  simulator's sensors, an example for the ROS node). A preset sets what its sensor needs
  (topics, per-point time convention, IMU noise, the lidar's mounting, ranges) and leaves the
  rest at the defaults below. Copy the closest one and change what your vehicle needs.
- **Every key is optional.** A key left out keeps the default listed here.
- **Mistakes are errors, not surprises.** An unknown key is an error naming its path and the
  keys known there; a key that moved or was removed says where it went; a key given twice in
  one map is an error naming both lines; a wrong type, or a value outside its constraint, is an
  error naming the key, the value and the constraint.
- **Every run saves its effective configuration** (every key, defaults included) as
  `config.yaml` beside its outputs; that file loads again as it is. `hylo config --defaults`
  prints the defaults in the same form; `hylo config --check FILE` checks a file without
  running anything.

Units are in the key names: `_m` metres, `_s` seconds, `_deg` degrees, `_rad` radians, `_mps`
m/s, `_mps2` m/s², `_radps` rad/s, `_hz` hertz, `_m2` m². A default is shown as a saved
configuration writes it; `.inf` is YAML's infinity.
)";

struct Row {
  std::string key, default_text, description;
};
struct DocSection {
  std::string path;
  std::string description;
  std::vector<Row> rows;
  std::vector<DocSection> children;
};

// A default as the YAML writer prints it (the same emitter, the same precision).
template <class T>
std::string YamlText(const T& value) {
  YAML::Emitter out;
  out.SetDoublePrecision(kYamlDoublePrecision);
  EmitYaml(&out, value);
  return out.c_str();
}

// For an enum, "; one of `a`, `b`": the names the reader takes, from the reader's own table.
template <class T>
std::string Allowed() {
  if constexpr (std::is_enum_v<T>) {
    std::string list;
    for (const std::string& name : EnumNames<T>()) {
      list += (list.empty() ? "`" : ", `") + name + "`";
    }
    return "; one of " + list;
  } else {
    return "";
  }
}

// Collects a section's keys and, after them, its nested sections.
class DocVisitor {
 public:
  explicit DocVisitor(DocSection* section) : section_(section) {}

  template <class T>
  void operator()(const char* key, T& value, const char* description) {
    HYLO_CHECK(description != nullptr && *description != '\0', "a field without a description");
    section_->rows.push_back({key, YamlText(value), description + Allowed<T>()});
  }

  template <class S>
  void Section(const char* key, S& section, const char* description) {
    HYLO_CHECK(description != nullptr && *description != '\0', "a section without a description");
    DocSection child;
    child.path = section_->path.empty() ? key : section_->path + "." + key;
    child.description = description;
    DocVisitor nested(&child);
    VisitFields(nested, section);
    section_->children.push_back(std::move(child));
  }

  template <class S>
  void OptionalSection(const char* key, S& section, bool& /*enabled*/, const char* description) {
    Section(key, section, description);
  }

 private:
  DocSection* section_;
};

// A table cell: a '|' would end the cell.
std::string Cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

// "the lidar stream" -> "The lidar stream."
std::string Sentence(std::string text) {
  if (!text.empty()) text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
  return text + ".";
}

// GitHub's anchor of a heading "`name`": lower case, punctuation other than - and _ dropped.
std::string Anchor(const std::string& name) {
  std::string anchor;
  for (char c : name) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '_' || c == '-') anchor += static_cast<char>(std::tolower(u));
  }
  return anchor;
}

void WriteTable(const std::vector<Row>& rows, std::ostringstream& md) {
  if (rows.empty()) return;
  md << "\n| key | default | meaning |\n|---|---|---|\n";
  for (const Row& r : rows) {
    md << "| `" << r.key << "` | `" << Cell(r.default_text) << "` | " << Cell(r.description)
       << " |\n";
  }
}

// "## `lidar`" for a top-level section, one more '#' per level of nesting.
void WriteSection(const DocSection& s, int depth, std::ostringstream& md) {
  md << "\n"
     << std::string(static_cast<std::size_t>(std::min(depth, 6)), '#') << " `" << s.path << "`\n\n"
     << Sentence(s.description) << "\n";
  WriteTable(s.rows, md);
  for (const DocSection& child : s.children) WriteSection(child, depth + 1, md);
}

}  // namespace

std::string ConfigurationReference() {
  RunConfig defaults;  // the visitor takes fields by non-const reference
  DocSection root;
  DocVisitor visitor(&root);
  VisitFields(visitor, defaults);

  std::ostringstream md;
  md << kIntro << "\n## Top level\n";
  WriteTable(root.rows, md);
  md << "\nSections:\n\n";
  for (const DocSection& s : root.children) {
    md << "- [`" << s.path << "`](#" << Anchor(s.path) << "): " << s.description << "\n";
  }
  for (const DocSection& s : root.children) WriteSection(s, 2, md);
  return md.str();
}

}  // namespace hylo::config
