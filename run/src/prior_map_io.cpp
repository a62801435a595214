#include "hylo/run/prior_map_io.h"

#include <filesystem>

#include "hylo/io/cloud_io.h"
#include "hylo/mapping/ikd_tree.h"
#include "hylo/tiles/tiled_prior_map.h"

namespace hylo::run {

mapping::PriorMap LoadPriorMap(const std::string& path, const mapping::PriorMapOptions& options,
                               const std::optional<Eigen::Isometry3d>& T_world_imu_guess,
                               odometry::OdometryPipeline* pipeline) {
  if (std::filesystem::is_directory(path)) {
    return tiles::LoadTiledPriorMap(path, options, T_world_imu_guess, pipeline);
  }
  mapping::PriorMap prior = mapping::BuildPriorMap(io::ReadCloud(path).positions, options, path);
  pipeline->SetPriorMap(prior.points_local);
  std::optional<Eigen::Isometry3d> guess_local;
  if (T_world_imu_guess) guess_local = mapping::PoseToLocal(*T_world_imu_guess, prior.origin_world);
  pipeline->SetInitialGuess(guess_local);
  return prior;
}

std::unique_ptr<registration::NeighborSearch> PriorSearch(
    const mapping::PriorMap& prior, const odometry::OdometryPipeline& pipeline,
    std::size_t cache_points) {
  if (!prior.tiled_dir.empty()) {
    return tiles::TiledPriorSearch(pipeline, cache_points);
  }
  auto tree = std::make_unique<mapping::IkdTree>();
  tree->Build(prior.points_local);
  return tree;
}

void WriteWorldCloud(const std::string& path, const PointCloud& points_map,
                     const Eigen::Vector3d& origin_world) {
  io::CloudFile file;
  file.positions.reserve(points_map.size());
  for (const Eigen::Vector3f& p : points_map) {
    file.positions.push_back(p.cast<double>() + origin_world);
  }
  // Compression is a PCD encoding; other formats are written in binary.
  const bool pcd = path.size() >= 4 && path.compare(path.size() - 4, 4, ".pcd") == 0;
  io::WriteCloud(path, file,
                 pcd ? io::CloudEncoding::kBinaryCompressed : io::CloudEncoding::kBinary);
}

}  // namespace hylo::run
