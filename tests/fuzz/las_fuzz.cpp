// Fuzz target: a LAS file (1.0-1.4, point formats 0-10; header, VLRs with the Extra Bytes
// descriptors, EVLRs, records) through ReadCloudInfo and ReadCloud (see cloud_fuzz.h).

#include "cloud_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  hylo::fuzz::FuzzCloudFile(data, size, "input.las");
  return 0;
}
