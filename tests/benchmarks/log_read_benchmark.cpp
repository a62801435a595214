// Reading speed of the same simulated session from every log format hylo reads: a ROS1 bag,
// a rosbag2 directory with sqlite3 storage, with MCAP storage (chunks stored) and with zstd
// MCAP chunks (and lz4). Each log is read whole through logs::OpenLog, the way `hylo map` reads
// it (scans decoded, IMU samples), several times; the best run's figures are reported: MB/s of
// the log's bytes and messages/s, per wall second (throughput: what a user waits for; the MCAP
// reader decompresses the next chunk on a second core meanwhile) and per CPU second (what the
// reader costs, summed over its threads). The logs are written once into --work by the
// simulator itself (`hylo simulate --format`'s path) and reused; they are read warm (in the
// page cache: what is compared is the readers, not the disk). Target: MCAP (stored and zstd)
// >= ROS1 in messages per wall second; the CPU ratios are reported beside it.
//
//   hylo_log_read_benchmark [--duration S] [--repeat N] [--work DIR] [--json PATH] [--quick]
//                           [--formats ros1,mcap-zstd,...]
// --formats reads only those (for whole-process timings of one reader at a time); the ratios
// to ROS1 need ros1 among them.

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "benchmark_common.h"
#include "hylo/logs/log_reader.h"
#include "hylo/logs/log_writer.h"
#include "hylo/sim_io/session_writer.h"

namespace hylo::benchmarks {
namespace {

namespace fs = std::filesystem;

struct Args {
  double duration_s = 60.0;
  int repeat = 5;
  std::string work = "/tmp/hylo_log_read_bench";
  std::string json = "log_read_benchmark.json";
  std::vector<logs::LogFormat> formats = {logs::LogFormat::kRos1, logs::LogFormat::kSqlite3,
                                          logs::LogFormat::kMcap, logs::LogFormat::kMcapZstd,
                                          logs::LogFormat::kMcapLz4};
};

// "ros1,mcap-zstd" -> the formats; false naming the first it does not know.
bool ParseFormats(const std::string& text, std::vector<logs::LogFormat>* out, std::string* bad) {
  out->clear();
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string name = text.substr(start, comma - start);
    logs::LogFormat format;
    if (!logs::ParseLogFormat(name, &format)) {
      *bad = name;
      return false;
    }
    out->push_back(format);
    start = comma + 1;
  }
  return !out->empty();
}

double CpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
         1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

uint64_t Bytes(const std::string& path) {
  if (!fs::is_directory(path)) return fs::file_size(path);
  uint64_t total = 0;
  for (const auto& e : fs::recursive_directory_iterator(path)) {
    if (e.is_regular_file()) total += e.file_size();
  }
  return total;
}

/// The session in `format`, simulated into `dir` unless it is there already.
std::string SessionLog(const Args& args, logs::LogFormat format) {
  const std::string dir = args.work + "/" + logs::ToString(format) + "_" +
                          std::to_string(static_cast<int>(args.duration_s)) + "s";
  const std::string log = sim::SessionLogPath(dir, sim::SessionId::kA, format);
  if (fs::exists(log)) return log;
  fs::remove_all(dir);
  sim::SimulationOptions options;
  options.duration_a_s = args.duration_s;
  const sim::Site site = sim::BuildSite(options.seed, options.terrain);
  const auto t0 = std::chrono::steady_clock::now();
  sim::WriteSession(options, site, sim::SessionId::kA, dir, {}, format);
  std::printf("simulated %s in %.1f s\n", log.c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return log;
}

struct ReadFigures {
  double wall_s = 1e300, cpu_s = 0.0;
  std::size_t messages = 0, points = 0;
};

/// The best of `repeat` complete reads (scans decoded), by wall time (each figure of that read).
ReadFigures Read(const std::string& log, int repeat) {
  ReadFigures best;
  for (int r = 0; r < repeat; ++r) {
    const double cpu0 = CpuSeconds();
    const auto t0 = std::chrono::steady_clock::now();
    auto reader = logs::OpenLog(log, logs::LogReadOptions());
    logs::LogMessage m;
    ReadFigures f;
    while (reader->Next(&m)) {
      ++f.messages;
      if (m.kind == logs::LogMessage::Kind::kScan) f.points += m.scan.points.size();
    }
    f.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    f.cpu_s = CpuSeconds() - cpu0;
    if (r == 0 || f.wall_s < best.wall_s) best = f;
  }
  return best;
}

int Main(int argc, char** argv) {
  Args args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (a == "--quick") {
      args.duration_s = 6.0;
      args.repeat = 1;
    } else if (a == "--duration") {
      args.duration_s = std::atof(value().c_str());
    } else if (a == "--repeat") {
      args.repeat = std::max(1, std::atoi(value().c_str()));
    } else if (a == "--work") {
      args.work = value();
    } else if (a == "--json") {
      args.json = value();
    } else if (a == "--formats") {
      std::string bad;
      if (!ParseFormats(value(), &args.formats, &bad)) {
        std::cerr << "--formats: unknown format '" << bad << "'\n";
        return 2;
      }
    } else {
      std::cerr << "usage: hylo_log_read_benchmark [--duration S] [--repeat N] [--work DIR] "
                   "[--json PATH] [--quick] [--formats ros1,mcap,...]\n";
      return 2;
    }
  }
  Report report;
  report.Set("session", "duration_s", args.duration_s);
  report.Set("session", "repeat", args.repeat);
  std::printf("%-10s %8s %11s %15s %9s %9s %13s %12s\n", "format", "MB", "MB/wall s",
              "messages/wall s", "wall s", "CPU s", "wall vs ROS1", "CPU vs ROS1");
  const bool with_ros1 = args.formats.front() == logs::LogFormat::kRos1;
  for (const logs::LogFormat format : args.formats) {
    const std::string log = SessionLog(args, format);
    const double mb = Bytes(log) / 1e6;
    const ReadFigures f = Read(log, args.repeat);
    std::string name = logs::ToString(format);
    std::replace(name.begin(), name.end(), '-', '_');
    const std::string section = "read_" + name;
    const double cpu_s = std::max(f.cpu_s, 1e-6);
    report.Set(section, "megabytes", mb);
    report.Set(section, "mb_per_s", mb / cpu_s);
    report.Set(section, "messages_per_s", f.messages / cpu_s);
    report.Set(section, "cpu_s", f.cpu_s);
    report.Set(section, "wall_s", f.wall_s);
    report.Set(section, "mb_per_wall_s", mb / f.wall_s);
    report.Set(section, "messages_per_wall_s", f.messages / f.wall_s);
    report.Set(section, "messages", f.messages);
    report.Set(section, "points", f.points);
    std::printf("%-10s %8.1f %11.1f %15.0f %9.3f %9.3f", logs::ToString(format).c_str(), mb,
                mb / f.wall_s, f.messages / f.wall_s, f.wall_s, f.cpu_s);
    if (with_ros1) {
      std::printf(" %13.2f %12.2f", report.Get("read_ros1", "wall_s") / f.wall_s,
                  report.Get("read_ros1", "cpu_s") / cpu_s);
    }
    std::printf("\n");
  }
  if (!with_ros1 || args.formats.size() != 5) {
    report.Print(std::cout);
    report.WriteJson(args.json);
    return 0;
  }
  // The same messages in every format: > 1 is faster than ROS1.
  const double ros1_wall = report.Get("read_ros1", "messages_per_wall_s");
  const double ros1_cpu = report.Get("read_ros1", "messages_per_s");
  for (const char* name : {"sqlite3", "mcap", "mcap_zstd", "mcap_lz4"}) {
    const std::string section = std::string("read_") + name;
    report.Set("targets", std::string(name) + "_over_ros1_wall",
               report.Get(section, "messages_per_wall_s") / ros1_wall);
    report.Set("targets", std::string(name) + "_over_ros1_cpu",
               report.Get(section, "messages_per_s") / ros1_cpu);
  }
  const bool met = report.Get("targets", "mcap_over_ros1_wall") >= 1.0 &&
                   report.Get("targets", "mcap_zstd_over_ros1_wall") >= 1.0;
  report.Set("targets", "mcap_at_least_ros1", met ? 1.0 : 0.0);
  report.Print(std::cout);
  std::printf("\ntarget MCAP (stored and zstd) >= ROS1 in messages per wall second: %s\n",
              met ? "met" : "NOT met");
  report.WriteJson(args.json);
  return 0;
}

}  // namespace
}  // namespace hylo::benchmarks

int main(int argc, char** argv) { return hylo::benchmarks::Main(argc, argv); }
