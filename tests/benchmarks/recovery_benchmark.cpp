// The randomized recovery benchmark: on each scenario (sim/scenario.h), localization drives
// that lose IMU and lidar while moving, lose the lidar alone, or begin while moving without a
// guess (tests/localization/recovery_scenario.h), each scored against the truth: recovered or
// not, time and distance driven to recovery, error after, wrong accepts, poses given as valid
// while > 1 m off, and the scan path's per-scan times while searching against while tracking.
// Prints one line per case and a table per back-end, case kind and half of the scenarios (the
// even ones are where defaults may be chosen, the odd ones are held out); writes JSON after
// every scenario. Figures are reported, never asserted.
//
//   hylo_recovery_benchmark [--scenarios 0-23] [--half even|odd|all] [--cases 6] [--seed S]
//                           [--window S] [--max-drive S] [--backends ieskf|sliding_window|both]
//                           [--background] [--real-time] [--jobs N] [--json PATH]
//                           [--preset-dir DIR] [--kinds K,K] [--trace DIR] [--quick] [--list]
//                           [--summarize A.json...]
// --background searches on a worker thread as the ROS node does (localization.search.background;
// off by default, as for a log read from a file, whose results then do not depend on the
// machine's load): the scan path's times while searching are then a live node's.
// --real-time delivers each case's scans from the data's return on at the pace of their stamps
// (with --background: the recovery time a live node would see, its attempt taking wall time).
// --kinds gap_all,gap_lidar,moving_start runs only the drawn cases of those kinds (same draws).
// --trace DIR writes every case's run scan by scan and its events (recovery_trace.h).
// --list prints the cases each scenario would run (where and when), simulating nothing.
// --jobs N runs N scenarios at once, each in a process of its own (this program again, with
// one scenario), and summarizes their JSON as one run.

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "hylo/io/json.h"
#include "recovery_summary.h"

extern char** environ;

namespace {

using hylo::estimation::Estimator;
using hylo::testing::RecoveryKind;
using hylo::testing::RecoveryScenario;

struct Args {
  std::vector<uint64_t> scenarios;
  bool background = false;
  std::string half = "all", backends = "ieskf";
  hylo::testing::RecoveryRunOptions run;
  int jobs = 1;
  bool quick = false, list = false;
  std::string json_path = "recovery_benchmark.json";
  std::vector<std::string> summarize;
};

// "0-5,8" -> 0 1 2 3 4 5 8.
bool ParseList(const std::string& text, std::vector<uint64_t>* out) {
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string part = text.substr(start, comma - start);
    char* end = nullptr;
    const uint64_t lo = std::strtoull(part.c_str(), &end, 10);
    const std::size_t dash = part.find('-');
    const uint64_t hi =
        dash == std::string::npos ? lo : std::strtoull(part.c_str() + dash + 1, &end, 10);
    if (part.empty() || end == part.c_str() || *end != '\0' || hi < lo) return false;
    for (uint64_t n = lo; n <= hi; ++n) out->push_back(n);
    start = comma + 1;
  }
  return !out->empty();
}

bool ParseBackends(const std::string& text, std::vector<Estimator::Backend>* out) {
  if (text == "both") {
    *out = {Estimator::Backend::kIeskf, Estimator::Backend::kSlidingWindow};
    return true;
  }
  Estimator::Backend backend;
  if (!hylo::estimation::ParseBackend(text, &backend)) return false;
  *out = {backend};
  return true;
}

bool Parse(int argc, char** argv, Args* args) {
  args->run.preset_dir = HYLO_PRESET_DIR;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has = i + 1 < argc;
    const auto number = [&] { return std::atof(argv[++i]); };
    if (a == "--scenarios" && has) {
      if (!ParseList(argv[++i], &args->scenarios)) return false;
    } else if (a == "--half" && has) {
      args->half = argv[++i];
      if (args->half != "even" && args->half != "odd" && args->half != "all") return false;
    } else if (a == "--cases" && has) {
      args->run.draw.cases = std::atoi(argv[++i]);
    } else if (a == "--seed" && has) {
      args->run.draw.seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (a == "--window" && has) {
      args->run.draw.window_s = number();
    } else if (a == "--max-drive" && has) {
      args->run.max_drive_s = number();
    } else if (a == "--backends" && has) {
      args->backends = argv[++i];
      if (!ParseBackends(args->backends, &args->run.backends)) return false;
    } else if (a == "--background") {
      args->background = true;
      args->run.adjust = [](hylo::odometry::OdometryPipelineOptions* o) {
        o->localization.search.background = true;
      };
    } else if (a == "--real-time") {
      args->run.real_time = true;
    } else if (a == "--jobs" && has) {
      args->jobs = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--json" && has) {
      args->json_path = argv[++i];
    } else if (a == "--preset-dir" && has) {
      args->run.preset_dir = argv[++i];
    } else if (a == "--kinds" && has) {
      std::stringstream names(argv[++i]);
      std::string name;
      while (std::getline(names, name, ',')) {
        RecoveryKind kind;
        if (!hylo::testing::ParseRecoveryKind(name, &kind)) return false;
        args->run.kinds.push_back(kind);
      }
    } else if (a == "--trace" && has) {
      args->run.trace_dir = argv[++i];
    } else if (a == "--quick") {
      args->quick = true;
    } else if (a == "--list") {
      args->list = true;
    } else if (a == "--summarize" && has) {
      while (i + 1 < argc && std::strncmp(argv[i + 1], "--", 2) != 0) {
        args->summarize.push_back(argv[++i]);
      }
    } else {
      std::fprintf(stderr, "unknown or incomplete argument '%s'\n", a.c_str());
      return false;
    }
  }
  if (args->quick) {
    // A smoke run: one 16-beam scenario, short drives, a kidnap and a moving start.
    args->scenarios = {1};
    args->run.max_drive_s = 40.0;
    args->run.draw.window_s = 15.0;
    args->run.specs = {{RecoveryKind::kGapAll, 8.0, 10.0}, {RecoveryKind::kMovingStart, 10.0}};
  }
  if (args->scenarios.empty()) {
    for (uint64_t n = 0; n < 24; ++n) args->scenarios.push_back(n);
  }
  std::vector<uint64_t> kept;
  for (const uint64_t n : args->scenarios) {
    if (args->half == "all" || static_cast<int>(n % 2) == (args->half == "odd" ? 1 : 0)) {
      kept.push_back(n);
    }
  }
  args->scenarios = kept;
  return args->run.draw.cases > 0 && args->run.draw.window_s > 0.0 &&
         (!args->scenarios.empty() || !args->summarize.empty());
}

std::vector<RecoveryScenario> ReadRuns(const std::vector<std::string>& paths) {
  std::vector<RecoveryScenario> all;
  for (const std::string& path : paths) {
    const hylo::io::Json j = hylo::io::ReadJsonFile(path);
    if (!j.contains("scenarios") || !j.at("scenarios").is_array()) {
      throw std::runtime_error(path + ": no 'scenarios' array");
    }
    for (const hylo::io::Json& s : j.at("scenarios")) {
      all.push_back(hylo::testing::RecoveryScenarioFromJson(s));
    }
  }
  return all;
}

// What the run was asked for, so that a JSON says how to reproduce it; a summary of other runs
// repeats the first one's.
hylo::io::Json RunSettings(const Args& args) {
  if (!args.summarize.empty()) {
    const hylo::io::Json first = hylo::io::ReadJsonFile(args.summarize.front());
    return first.contains("settings") ? first.at("settings") : hylo::io::Json();
  }
  return {{"cases_per_scenario", args.run.draw.cases},
          {"seed", args.run.draw.seed},
          {"window_s", args.run.draw.window_s},
          {"max_drive_s", args.run.max_drive_s},
          {"background_search", args.background},
          {"real_time", args.run.real_time},
          {"quick", args.quick}};
}

hylo::io::Json Document(const std::vector<RecoveryScenario>& all, const Args& args) {
  hylo::io::Json out = hylo::io::Json::object();
  out["settings"] = RunSettings(args);
  out["note"] =
      "positions in the prior map's frame without alignment; times from the data's return (the "
      "log's start) to a valid pose within 1 m that holds 5 s; scan times are per scan, thread "
      "CPU and wall, on a shared machine";
  out["scenarios"] = hylo::io::Json::array();
  for (const RecoveryScenario& s : all) out["scenarios"].push_back(hylo::testing::ToJson(s));
  return out;
}

// Prints the table and writes every scenario, the table and the totals (the first back-end,
// every kind, every scenario: what the smoke test checks).
void Finish(const std::vector<RecoveryScenario>& all, const Args& args) {
  const std::string& json_path = args.json_path;
  hylo::io::Json out = Document(all, args);
  out["summary"] = hylo::benchmarks::PrintSummary(all);
  if (!all.empty() && !all.front().results.empty()) {
    out["totals"] = hylo::benchmarks::ToJson(
        hylo::benchmarks::Summarize(all, all.front().results.front().backend, "", -1));
  }
  hylo::io::WriteJsonFile(json_path, out);
  std::printf("\nJSON: %s\n", json_path.c_str());
}

void List(const Args& args) {
  for (const uint64_t n : args.scenarios) {
    const hylo::sim::Scenario scenario = hylo::sim::DrawScenario(n);
    std::vector<Eigen::Vector3d> where;
    const auto cases = hylo::testing::PlanRecoveryCases(scenario, args.run, &where);
    std::printf("#%-3llu %s\n", static_cast<unsigned long long>(n), scenario.Summary().c_str());
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const hylo::testing::RecoveryCase& c = cases[k];
      std::printf(
          "  %2d %-12s cut %6.1f s, back %6.1f s (%5.1f m, drawn %5.1f m), %.1f m/s at "
          "(%.1f, %.1f) m\n",
          c.index, hylo::testing::ToString(c.kind).c_str(),
          1e-9 * double(c.cut_t_ns - scenario.start_b_ns),
          1e-9 * double(c.return_t_ns - scenario.start_b_ns), c.distance_m, c.drawn_distance_m,
          c.speed_mps, where[k].x(), where[k].y());
    }
  }
}

// The path of this program, for its children.
std::string SelfPath() {
  char path[4096];
  const ssize_t n = ::readlink("/proc/self/exe", path, sizeof(path) - 1);
  if (n <= 0) throw std::runtime_error("cannot read /proc/self/exe");
  return std::string(path, static_cast<std::size_t>(n));
}

// Each scenario in a child process (this program with one scenario), `jobs` at a time.
std::vector<RecoveryScenario> RunInChildren(const Args& args, int argc, char** argv) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("hylo_recovery_" + std::to_string(static_cast<long long>(::getpid())));
  std::filesystem::create_directories(dir);
  const std::string self = SelfPath();
  std::map<pid_t, uint64_t> running;
  std::vector<std::string> paths;
  std::size_t next = 0;
  bool failed = false;
  while (next < args.scenarios.size() || !running.empty()) {
    if (next < args.scenarios.size() && static_cast<int>(running.size()) < args.jobs) {
      const uint64_t n = args.scenarios[next++];
      paths.push_back((dir / (std::to_string(n) + ".json")).string());
      std::vector<std::string> words = {self};
      for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--jobs" || a == "--json" || a == "--scenarios" || a == "--half") {
          ++i;  // replaced below
        } else {
          words.push_back(a);
        }
      }
      words.insert(words.end(), {"--scenarios", std::to_string(n), "--json", paths.back()});
      std::vector<char*> child_argv;
      for (std::string& w : words) child_argv.push_back(w.data());
      child_argv.push_back(nullptr);
      pid_t pid = 0;
      if (posix_spawn(&pid, child_argv[0], nullptr, nullptr, child_argv.data(), environ) != 0) {
        throw std::runtime_error("cannot start a child for scenario " + std::to_string(n));
      }
      running[pid] = n;
      continue;
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) break;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::fprintf(stderr, "scenario %llu: the child failed (status %d)\n",
                   static_cast<unsigned long long>(running[pid]), status);
      failed = true;
    }
    running.erase(pid);
  }
  if (failed) throw std::runtime_error("a scenario's process failed; its JSON is left out");
  std::vector<RecoveryScenario> all = ReadRuns(paths);
  std::filesystem::remove_all(dir);
  return all;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (!Parse(argc, argv, &args)) {
    std::fprintf(stderr,
                 "usage: hylo_recovery_benchmark [--scenarios 0-23] [--half even|odd|all] "
                 "[--cases 6] [--seed S] [--window S] [--max-drive S] "
                 "[--backends ieskf|sliding_window|both] [--background] [--real-time] [--jobs N] "
                 "[--json PATH] [--preset-dir DIR] [--kinds K,K] [--trace DIR] [--quick] [--list] "
                 "[--summarize A.json...]\n");
    return 2;
  }
  try {
    if (args.list) {
      List(args);
      return 0;
    }
    if (!args.summarize.empty()) {
      const std::vector<RecoveryScenario> all = ReadRuns(args.summarize);
      for (const RecoveryScenario& s : all) hylo::benchmarks::PrintCases(s);
      Finish(all, args);
      return 0;
    }
    if (args.jobs > 1 && args.scenarios.size() > 1) {
      Finish(RunInChildren(args, argc, argv), args);
      return 0;
    }
    std::vector<RecoveryScenario> all;
    for (const uint64_t n : args.scenarios) {
      all.push_back(hylo::testing::RunRecoveryScenario(hylo::sim::DrawScenario(n), args.run));
      hylo::benchmarks::PrintCases(all.back());
      hylo::io::WriteJsonFile(args.json_path, Document(all, args));
    }
    Finish(all, args);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
