// Fuzz target: a JSON file (summaries, manifests, the runs `hylo compare` reads back) through
// ReadJsonFile and NumberAt; what it accepts must survive DumpJson -> parse unchanged.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz_support.h"
#include "hylo/io/json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string path = hylo::fuzz::WriteScratchFile("input.json", data, size);
  hylo::io::Json json;
  try {
    json = hylo::io::ReadJsonFile(path);
  } catch (const std::runtime_error& e) {
    hylo::fuzz::RequireClearError(e, path);
    return 0;
  }
  // Dotted paths made of the document's own keys, one level and two levels deep.
  if (json.is_object()) {
    for (const auto& [key, value] : json.items()) {
      hylo::io::NumberAt(json, key);
      if (!value.is_object()) continue;
      for (const auto& [inner, unused] : value.items()) hylo::io::NumberAt(json, key + "." + inner);
    }
  }
  const std::string dumped = hylo::io::DumpJson(json);
  hylo::fuzz::Require(hylo::io::Json::parse(dumped) == json,
                      "DumpJson does not read back: " + dumped);
  return 0;
}
