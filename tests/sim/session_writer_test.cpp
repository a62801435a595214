// Files: same seed -> the same bytes (bag, truth, manifest, reference cloud, slope grid);
// the bag reads back with the rates and the per-point time field; the truth file matches.
#include "hylo/sim_io/session_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "hylo/io/cloud_io.h"
#include "hylo/logs/log_reader.h"
#include "hylo/sim_io/reference_outputs.h"

namespace hylo::sim {
namespace {

namespace fs = std::filesystem;

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(HYLO_BINARY_DIR) / "test_output" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void WriteAll(const SimulationOptions& options, const fs::path& dir) {
  const Site site = BuildSite(options.seed, options.terrain);
  WriteSession(options, site, SessionId::kA, dir.string());
  WriteSession(options, site, SessionId::kB, dir.string());
  SiteOutputOptions output;
  output.reference_spacing_m = 0.3;
  WriteSiteOutputs(options, site, output, dir.string());
}

TEST(SessionWriter, SameSeedGivesTheSameBytes) {
  const SimulationOptions options = SimulationOptions::Fast(1.5);
  const fs::path first = FreshDir("sim_same_1"), second = FreshDir("sim_same_2");
  WriteAll(options, first);
  WriteAll(options, second);
  int compared = 0;
  for (const auto& entry : fs::directory_iterator(first)) {
    const std::string a = ReadBytes(entry.path());
    const std::string b = ReadBytes(second / entry.path().filename());
    ASSERT_FALSE(a.empty()) << entry.path();
    EXPECT_TRUE(a == b) << entry.path().filename() << " differs between two runs";
    ++compared;
  }
  EXPECT_EQ(compared, 9);  // 2 x (bag, truth, manifest) + reference, slope, site.json
}

TEST(SessionWriter, BagReadsBackWithRatesAndTimeField) {
  const SimulationOptions options = SimulationOptions::Fast(2.0);
  const fs::path dir = FreshDir("sim_readback");
  const Site site = BuildSite(options.seed, options.terrain);
  const SessionSummary summary = WriteSession(options, site, SessionId::kA, dir.string());
  auto reader = logs::OpenLog(SessionBagPath(dir.string(), SessionId::kA), logs::LogReadOptions{});
  logs::LogMessage message;
  std::vector<int64_t> imu_t, scan_t;
  std::size_t points = 0;
  int64_t max_offset = 0;
  while (reader->Next(&message)) {
    if (message.kind == logs::LogMessage::Kind::kImu) {
      imu_t.push_back(message.imu.t_ns);
    } else {
      scan_t.push_back(message.scan.t_ns);
      points += message.scan.points.size();
      for (const auto& p : message.scan.points)
        max_offset = std::max<int64_t>(max_offset, p.offset_ns);
    }
  }
  EXPECT_EQ(reader->time_convention(), logs::PointTimeConvention::kVelodyne);
  ASSERT_EQ(imu_t.size(), summary.imu_samples);
  ASSERT_EQ(scan_t.size(), summary.scans);
  EXPECT_EQ(points, summary.points);
  std::sort(imu_t.begin(), imu_t.end());
  std::sort(scan_t.begin(), scan_t.end());
  EXPECT_NEAR(1e9 / double(imu_t[1] - imu_t[0]), 200.0, 1e-6);
  EXPECT_NEAR(1e9 / double(scan_t[1] - scan_t[0]), 10.0, 1e-6);
  EXPECT_GT(max_offset, 90'000'000);  // the time field survives (float seconds -> ns)
  EXPECT_LT(max_offset, 100'000'000);
}

TEST(SessionWriter, ReferenceCloudHasLabelledGroundAndObjects) {
  const SimulationOptions options = SimulationOptions::Fast(1.0);
  const Site site = BuildSite(options.seed, options.terrain);
  const World world(site.terrain, SessionPrimitives(site, SessionId::kA));
  const io::CloudFile cloud = ReferenceCloud(site, world, 0.3, options.seed);
  ASSERT_EQ(cloud.labels.size(), cloud.positions.size());
  std::size_t ground = 0, objects = 0;
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    const Eigen::Vector3d& p = cloud.positions[i];
    if (cloud.labels[i] == kLabelGround) {
      ++ground;
      ASSERT_NEAR(p.z(), site.terrain->Height(p.x(), p.y()), 1e-9);
    } else {
      ++objects;
      ASSERT_EQ(cloud.labels[i], kLabelObject);
      ASSERT_GE(p.z(), site.terrain->Height(p.x(), p.y()) - 0.011);
    }
  }
  EXPECT_GT(ground, 50000u);
  EXPECT_GT(objects, 10000u);
}

}  // namespace
}  // namespace hylo::sim
