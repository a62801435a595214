// Fuzz target: a rosbag2 recording's metadata.yaml, parsed (every version's keys, any YAML) and
// then resolved as a recording directory holding only it: a malformed or mistyped file, or one
// naming storage files that are not there, is refused with one line naming the file or the
// directory; nothing else escapes (no yaml-cpp exception, no crash).

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>

#include "fuzz_support.h"
#include "rosbag2_metadata.h"
#include "rosbag2_stream.h"

namespace detail = hylo::logs::detail;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const detail::Rosbag2Metadata m = detail::ParseRosbag2Metadata(text, "metadata.yaml");
    hylo::fuzz::Require(m.version != 0 || text.find("version") != std::string::npos,
                        "parsed without a version");
  } catch (const std::runtime_error& e) {
    hylo::fuzz::RequireClearError(e, "metadata.yaml");
  }
  const std::string dir = hylo::fuzz::FreshScratchFolder("bag");
  std::ofstream(dir + "/metadata.yaml", std::ios::binary) << text;
  try {
    detail::Rosbag2Stream stream(detail::ResolveRosbag2(dir));
  } catch (const std::runtime_error& e) {
    hylo::fuzz::RequireClearError(e, dir);
  }
  return 0;
}
