#pragma once
// The body shared by the point cloud file targets (PCD, PLY, KITTI .bin): the input becomes a
// file with the format's extension and goes through the readers `hylo` uses on it
// (ReadCloudInfo for `hylo info`, ReadCloud for everything else).

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz_support.h"
#include "hylo/io/cloud_io.h"

namespace hylo::fuzz {

inline void CheckCloud(const io::CloudFile& cloud) {
  const std::size_t n = cloud.positions.size();
  Require(cloud.intensity.empty() || cloud.intensity.size() == n, "intensity size mismatch");
  Require(cloud.normals.empty() || cloud.normals.size() == n, "normals size mismatch");
  Require(cloud.labels.empty() || cloud.labels.size() == n, "labels size mismatch");
  for (const Eigen::Vector3d& p : cloud.positions) {
    Require(p.allFinite(), "a non-finite position was kept");
  }
}

inline void FuzzCloudFile(const uint8_t* data, std::size_t size, const std::string& name) {
  const std::string path = WriteScratchFile(name, data, size);
  std::size_t announced = 0;
  bool header_read = false;
  try {
    announced = io::ReadCloudInfo(path).points;
    header_read = true;
  } catch (const std::runtime_error& e) {
    RequireClearError(e, path);
  }
  try {
    const io::CloudFile cloud = io::ReadCloud(path);
    CheckCloud(cloud);
    Require(header_read, "ReadCloud accepted a file whose header ReadCloudInfo refused");
    Require(cloud.positions.size() + cloud.dropped_non_finite == announced,
            "points read + dropped differ from the points the header announces");
  } catch (const std::runtime_error& e) {
    RequireClearError(e, path);
  }
}

}  // namespace hylo::fuzz
