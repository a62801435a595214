// Fuzz target: a PLY file (ascii, binary little and big endian) through ReadCloudInfo and ReadCloud
// (see cloud_fuzz.h).

#include "cloud_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  hylo::fuzz::FuzzCloudFile(data, size, "input.ply");
  return 0;
}
