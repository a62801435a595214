#include "benchmarks/isprs_eval.h"

#include <cmath>
#include <cstdio>
#include <unordered_set>

#include "hylo/io/cloud_io.h"
#include "test_data.h"

namespace hylo::terrain::isprs {

PointKey KeyOf(const Eigen::Vector3d& p) {
  return {std::llround(p.x() * 1000), std::llround(p.y() * 1000), std::llround(p.z() * 1000)};
}

double Confusion::Kappa() const {
  const double observed = (ground_as_ground + object_as_object) / N();
  const double truth_ground = ground_as_ground + ground_as_object;
  const double said_ground = ground_as_ground + object_as_ground;
  const double chance =
      (truth_ground * said_ground + (N() - truth_ground) * (N() - said_ground)) / (N() * N());
  return (observed - chance) / (1.0 - chance);
}

const std::vector<std::string>& SampleNames() {
  static const std::vector<std::string> names = {"samp11", "samp21", "samp31", "samp41",
                                                 "samp51", "samp52", "samp61"};
  return names;
}

Sample LoadSample(const std::string& name) {
  Sample sample;
  sample.name = name;
  sample.points = io::ReadCloud(hylo::testing::DataPath("isprs/" + name + "-utm.pcd")).positions;
  const io::CloudFile ground =
      io::ReadCloud(hylo::testing::DataPath("isprs/" + name + "-utm-ground.pcd"));
  std::unordered_set<PointKey, PointKeyHash> ground_keys;
  for (const Eigen::Vector3d& p : ground.positions) ground_keys.insert(KeyOf(p));
  sample.is_ground.reserve(sample.points.size());
  for (const Eigen::Vector3d& p : sample.points) {
    sample.is_ground.push_back(ground_keys.count(KeyOf(p)) > 0);
  }
  return sample;
}

Confusion Score(const Sample& sample, const std::vector<GroundLabel>& labels) {
  Confusion c;
  for (std::size_t i = 0; i < sample.points.size(); ++i) {
    const bool said = labels[i] == GroundLabel::kGround;
    (sample.is_ground[i] ? (said ? c.ground_as_ground : c.ground_as_object)
                         : (said ? c.object_as_ground : c.object_as_object)) += 1;
  }
  return c;
}

const char* TableHeader() { return "sample   typeI%  typeII%  total%  kappa%"; }

std::string TableRow(const std::string& name, const Confusion& c) {
  char row[96];
  std::snprintf(row, sizeof(row), "%-7s %7.2f %8.2f %7.2f %7.2f", name.c_str(), 100 * c.TypeI(),
                100 * c.TypeII(), 100 * c.Total(), 100 * c.Kappa());
  return row;
}

}  // namespace hylo::terrain::isprs
