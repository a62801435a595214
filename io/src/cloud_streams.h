#pragma once
// Internal to hylo::io: the format-specific streams behind CloudStream::Open (cloud_stream.h).

#include <memory>
#include <string>

#include "hylo/io/cloud_stream.h"

namespace hylo::io::internal {

/// `whole`: the caller reads everything, so a binary_compressed block is decompressed at once.
std::unique_ptr<CloudStream> OpenPcdStream(const std::string& path, bool whole);
std::unique_ptr<CloudStream> OpenPlyStream(const std::string& path);
std::unique_ptr<CloudStream> OpenKittiStream(const std::string& path);
std::unique_ptr<CloudStream> OpenLasStream(const std::string& path);

}  // namespace hylo::io::internal
