// Point cloud file speed: LAS against binary PCD on the same cloud (1M points by default), whole
// writes, whole reads and chunked reads (the way `hylo tile` reads a map), as MB/s of file and
// M points/s. Two clouds: a site in UTM coordinates (PCD needs float64 positions) and the same
// site near zero (PCD stores float32); both carry intensity and a class label. Each figure is
// the best of 3 runs (files in the page cache: the formats' encode/decode, not the disk).
//   hylo_cloud_io_benchmark [--points N] [--quick] [--json out.json] [--dir /tmp]

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include "benchmark_common.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/cloud_stream.h"

namespace {

namespace io = hylo::io;

io::CloudFile Site(std::size_t n, const Eigen::Vector3d& origin) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> xy(0.0, 400.0), z(0.0, 12.0);
  std::uniform_int_distribution<int> intensity(0, 4095), label(1, 18);
  io::CloudFile cloud;
  cloud.positions.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    // On the 0.1 mm grid, so that both formats store the same positions.
    const Eigen::Vector3d p(xy(rng), xy(rng), z(rng));
    cloud.positions.push_back(origin + (p * 1e4).array().round().matrix() * 1e-4);
    cloud.intensity.push_back(static_cast<float>(intensity(rng)));
    cloud.labels.push_back(label(rng));
  }
  return cloud;
}

template <typename F>
double BestSeconds(F&& f) {
  double best = 1e300;
  for (int run = 0; run < 3; ++run) {
    const auto start = std::chrono::steady_clock::now();
    f();
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

void Measure(const std::string& section, const io::CloudFile& cloud, const std::string& path,
             hylo::benchmarks::Report* report) {
  const double points = static_cast<double>(cloud.positions.size());
  const double write_s = BestSeconds([&] { io::WriteCloud(path, cloud); });
  const double mb = 1e-6 * static_cast<double>(std::filesystem::file_size(path));
  std::size_t read_points = 0;
  const double read_s = BestSeconds([&] { read_points = io::ReadCloud(path).positions.size(); });
  const double stream_s = BestSeconds([&] {
    std::unique_ptr<io::CloudStream> stream = io::CloudStream::Open(path);
    io::CloudFile chunk;
    while (stream->Next(std::size_t{1} << 20, &chunk)) {
    }
  });
  if (read_points != cloud.positions.size())
    std::fprintf(stderr, "%s: points lost\n", path.c_str());
  report->Set(section, "file_mb", mb);
  report->Set(section, "bytes_per_point", 1e6 * mb / points);
  report->Set(section, "write_mb_per_s", mb / write_s);
  report->Set(section, "read_mb_per_s", mb / read_s);
  report->Set(section, "stream_mb_per_s", mb / stream_s);
  report->Set(section, "write_mpoints_per_s", 1e-6 * points / write_s);
  report->Set(section, "read_mpoints_per_s", 1e-6 * points / read_s);
  report->Set(section, "stream_mpoints_per_s", 1e-6 * points / stream_s);
  std::filesystem::remove(path);
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t n = 1000000;
  std::string json, dir = "/tmp";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") n = 100000;
    if (a == "--points" && i + 1 < argc) n = std::stoul(argv[++i]);
    if (a == "--json" && i + 1 < argc) json = argv[++i];
    if (a == "--dir" && i + 1 < argc) dir = argv[++i];
  }
  hylo::benchmarks::Report report;
  const std::string stem = dir + "/hylo_cloud_io_" + std::to_string(::getpid());
  for (const bool utm : {true, false}) {
    const io::CloudFile cloud =
        Site(n, utm ? Eigen::Vector3d(512000.0, 5403000.0, 200.0) : Eigen::Vector3d::Zero());
    const std::string where = utm ? "utm" : "local";
    Measure("pcd_binary_" + where, cloud, stem + ".pcd", &report);
    Measure("las_" + where, cloud, stem + ".las", &report);
    for (const char* kind : {"read", "write", "stream"}) {
      const std::string key = std::string(kind) + "_mpoints_per_s";
      report.Set("las_over_pcd_" + where, kind,
                 report.Get("las_" + where, key) / report.Get("pcd_binary_" + where, key));
    }
  }
  report.Set("cloud", "points", static_cast<double>(n));
  report.Print(std::cout);
  if (!json.empty() && !report.WriteJson(json)) {
    std::fprintf(stderr, "cannot write %s\n", json.c_str());
    return 1;
  }
  return 0;
}
