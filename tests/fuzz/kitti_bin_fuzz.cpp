// Fuzz target: a KITTI .bin scan (float32 x y z intensity records) through ReadCloudInfo and
// ReadCloud (see cloud_fuzz.h).

#include "cloud_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  hylo::fuzz::FuzzCloudFile(data, size, "input.bin");
  return 0;
}
