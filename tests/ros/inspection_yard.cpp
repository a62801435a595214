#include "inspection_yard.h"

#include <filesystem>
#include <fstream>
#include <vector>

#include "hylo/io/cloud_io.h"
#include "hylo/io/costmap_io.h"
#include "hylo/terrain/traversability.h"

namespace hylo::testing {

InspectionYard WriteInspectionYard(const std::string& dir, const Eigen::Vector3d& offset) {
  std::filesystem::create_directories(dir);
  std::vector<Eigen::Vector3d> ground, wall;
  for (double x = 0.05; x < 30.0; x += 0.1)
    for (double y = 0.05; y < 20.0; y += 0.1) ground.push_back(offset + Eigen::Vector3d(x, y, 0));
  for (double x = 12.0; x <= 12.2 + 1e-6; x += 0.05)
    for (double y = 0.0; y <= 14.0 + 1e-6; y += 0.05)
      for (double z = 0.05; z <= 3.0 + 1e-6; z += 0.05)
        wall.push_back(offset + Eigen::Vector3d(x, y, z));
  InspectionYard yard{dir + "/map.pcd", dir + "/costmap", dir + "/targets.csv", offset};
  io::CloudFile map;
  map.positions = ground;
  map.positions.insert(map.positions.end(), wall.begin(), wall.end());
  io::WriteCloud(yard.map, map);
  io::WriteTraversabilityFiles(
      yard.costmap_dir,
      terrain::ComputeTraversability(ground, wall, terrain::TraversabilityOptions()));
  std::ofstream targets(yard.targets);
  targets.precision(12);
  targets << "id,x,y,z\n"
          << "open," << offset.x() + 6 << "," << offset.y() + 10 << "," << offset.z() + 1.5 << "\n"
          << "behind_wall," << offset.x() + 16 << "," << offset.y() + 5 << "," << offset.z() + 1.5
          << "\n";
  return yard;
}

}  // namespace hylo::testing
