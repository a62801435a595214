// Fuzz target: the YAML run configuration through ParseRunConfig; a configuration it accepts
// must survive ToYaml -> ParseRunConfig unchanged (every run saves it next to its outputs and
// a user loads it again).

#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "hylo/config/run_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  hylo::config::RunConfig config;
  try {
    config = hylo::config::ParseRunConfig(text, "fuzz.yaml");
  } catch (const hylo::config::ConfigError& e) {
    hylo::fuzz::Require(std::string(e.what()).find("fuzz.yaml") != std::string::npos,
                        std::string("error does not name the file: ") + e.what());
    return 0;
  }
  config.LogOptions();
  config.PipelineOptions();
  const std::string saved = hylo::config::ToYaml(config);
  try {
    const hylo::config::RunConfig again = hylo::config::ParseRunConfig(saved, "saved.yaml");
    hylo::fuzz::Require(hylo::config::ToYaml(again) == saved,
                        "the saved configuration loads as a different one:\n" + saved);
  } catch (const hylo::config::ConfigError& e) {
    hylo::fuzz::Fail(std::string("the saved configuration does not load: ") + e.what() + "\n" +
                     saved);
  }
  return 0;
}
