// The field list's other writers: the JSON of a configuration and the reference doc.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "hylo/config/config_doc.h"
#include "hylo/config/config_json.h"
#include "hylo/config/run_config.h"

namespace hylo::config {
namespace {

const char* const kRegenerate = "build/apps/hylo config --doc --out docs/configuration.md";

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The key paths of a YAML map and of a JSON object, nested sections included.
void YamlKeys(const YAML::Node& node, const std::string& path, std::vector<std::string>* keys) {
  for (const auto& entry : node) {
    const std::string key = path + entry.first.Scalar();
    keys->push_back(key);
    if (entry.second.IsMap()) YamlKeys(entry.second, key + ".", keys);
  }
}
void JsonKeys(const io::Json& json, const std::string& path, std::vector<std::string>* keys) {
  for (const auto& [name, value] : json.items()) {
    keys->push_back(path + name);
    if (value.is_object()) JsonKeys(value, path + name + ".", keys);
  }
}

// The JSON writer and the YAML writer walk the same list: same keys, same order.
TEST(ConfigJson, HasEveryKeyOfTheSavedYaml) {
  RunConfig config;
  std::vector<std::string> yaml_keys, json_keys;
  YamlKeys(YAML::Load(ToYaml(config)), "", &yaml_keys);
  JsonKeys(ToJson(config), "", &json_keys);
  EXPECT_EQ(json_keys, yaml_keys);
  EXPECT_GT(json_keys.size(), 150u);
}

TEST(ConfigJson, WritesValuesAsTheConfigurationDoes) {
  RunConfig config;
  config.pipeline.estimator.backend = estimation::Estimator::Backend::kSlidingWindow;
  config.T_imu_lidar.translation_m = {0.1, -0.2, 0.3};
  config.lidar.topic = "/velodyne_points";
  const io::Json json = ToJson(config);
  EXPECT_EQ(json["backend"], "sliding_window");
  EXPECT_EQ(json["lidar"]["topic"], "/velodyne_points");
  EXPECT_EQ(json["lidar"]["time_convention"], "auto");
  EXPECT_EQ(json["T_imu_lidar"]["translation_m"], io::Json::array({0.1, -0.2, 0.3}));
  EXPECT_EQ(json["ground"]["method"], "smrf");
  EXPECT_DOUBLE_EQ(json["preprocess"]["min_range_m"].get<double>(), 0.5);
  config.pipeline.imu.enabled = false;
  EXPECT_EQ(ToJson(config)["imu"], "none");
}

// `hylo ground --json` records its back-end's options through these; the cloth filter's
// damping was once left out of a hand-written copy.
TEST(ConfigJson, GroundBackEndsCarryEveryOption) {
  terrain::ClothFilterOptions csf;
  csf.damping = 0.25;
  csf.slope_max_cloth_gap_m = std::numeric_limits<double>::infinity();
  const io::Json json = ToJson(csf);
  EXPECT_DOUBLE_EQ(json["damping"].get<double>(), 0.25);
  EXPECT_EQ(io::DumpJson(json["slope_max_cloth_gap_m"]), "null");  // no limit
  EXPECT_EQ(json["hole_fill"], terrain::ToString(csf.hole_fill));
  const RunConfig defaults;
  EXPECT_EQ(ToJson(defaults.ground), ToJson(defaults)["ground"]);
  EXPECT_EQ(ToJson(defaults.ground.csf), ToJson(defaults)["ground"]["csf"]);
  EXPECT_EQ(ToJson(defaults.ground.smrf), ToJson(defaults)["ground"]["smrf"]);
}

TEST(ConfigurationDoc, ListsEverySectionKeyDefaultAndEnumValue) {
  const std::string doc = ConfigurationReference();
  for (const char* fragment :
       {"## `lidar`", "### `imu.noise`", "### `localization.icp`", "### `ground.csf`",
        "| `backend` | `ieskf` |", "`sliding_window`", "| `topic` | `/points` |",
        "| `translation_m` | `[0, 0, 0]` |", "| `damping` |", "`sparse_normal_cholesky`",
        "`geman_mcclure`", "`reference`", "| `initial_guess` | `\"\"` |", "config/presets/",
        "config.yaml"}) {
    EXPECT_NE(doc.find(fragment), std::string::npos) << "the reference lacks " << fragment;
  }
}

// docs/configuration.md is generated; a field or description changed without regenerating it
// fails here, with the command that brings it up to date.
TEST(ConfigurationDoc, CommittedFileIsCurrent) {
  const std::string path = std::string(HYLO_SOURCE_DIR) + "/docs/configuration.md";
  std::ifstream file(path);
  ASSERT_TRUE(file) << path << " is missing; generate it with: " << kRegenerate;
  std::stringstream committed;
  committed << file.rdbuf();
  const std::string generated = ConfigurationReference();
  if (committed.str() == generated) return;
  const std::vector<std::string> a = Lines(committed.str()), b = Lines(generated);
  std::size_t i = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
  FAIL() << path << " differs from the field list at line " << i + 1
         << ":\n  committed: " << (i < a.size() ? a[i] : "(end of file)")
         << "\n  generated: " << (i < b.size() ? b[i] : "(end of file)")
         << "\nRegenerate it with: " << kRegenerate;
}

}  // namespace
}  // namespace hylo::config
