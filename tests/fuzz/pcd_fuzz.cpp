// Fuzz target: a PCD file (ascii, binary, binary_compressed with its LZF block) through
// ReadCloudInfo and ReadCloud (see cloud_fuzz.h).

#include "cloud_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  hylo::fuzz::FuzzCloudFile(data, size, "input.pcd");
  return 0;
}
