// Each back-end in a child `hylo compare --only-backend` process, read back and evaluated.
#include "backend_runs.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "hylo/config/run_config.h"
#include "hylo/estimation/estimator.h"
#include "hylo/io/json.h"
#include "hylo/localization/pose_guess.h"
#include "hylo/run/run_log.h"

extern char** environ;

namespace hylo::cli {
namespace {

// This process's own peak resident memory (VmHWM), MiB. Not getrusage's ru_maxrss: Linux
// carries the parent's high-water mark across fork + exec into it, so a child started by a
// large `hylo demo` would report the parent's memory.
double OwnPeakMemoryMb() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
  }
  return std::nan("");
}

std::string FirstLine(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

std::string SelfExecutable() {
  char path[4096];
  const ssize_t n = readlink("/proc/self/exe", path, sizeof(path) - 1);
  if (n <= 0)
    throw std::runtime_error(std::string("cannot find the hylo executable: ") +
                             std::strerror(errno));
  return std::string(path, static_cast<std::size_t>(n));
}

std::vector<std::string> ChildArguments(const BackendRunsRequest& r, const std::string& backend) {
  std::vector<std::string> args{SelfExecutable(), "compare",     "--log", r.log,
                                "--config",       r.config_path, "--out", r.out_dir,
                                "--only-backend", backend};
  if (!r.prior_map.empty()) args.insert(args.end(), {"--map", r.prior_map, "--guess", r.guess});
  return args;
}

// Runs the child to completion; its stdout/stderr are ours (progress stays visible).
// Returns the exit status, or -1 with *error when it did not run or was killed.
int RunChild(const std::vector<std::string>& args, std::string* error) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  pid_t pid = 0;
  // /proc/self/exe, not the path: it still runs this very executable when a rebuild has
  // replaced the file meanwhile.
  const int rc = posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, argv.data(), environ);
  if (rc != 0) {
    *error = "cannot start " + args[0] + ": " + std::strerror(rc);
    return -1;
  }
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) {
    *error = std::string("waiting for the child failed: ") + std::strerror(errno);
    return -1;
  }
  if (WIFSIGNALED(status)) {
    *error = "killed by signal " + std::to_string(WTERMSIG(status)) + " (" +
             strsignal(WTERMSIG(status)) + ")";
    return -1;
  }
  return WEXITSTATUS(status);
}

std::vector<evaluation::TimedPose> ToTimed(const std::vector<io::StampedPose>& poses) {
  std::vector<evaluation::TimedPose> out;
  for (const io::StampedPose& p : poses) out.push_back({p.t_ns, p.T_world_body()});
  return out;
}

// The figures of a finished child run, from its files.
void ReadChildOutputs(const BackendRunsRequest& request, BackendRun* run) {
  const io::Json summary = io::ReadJsonFile(run->dir + "/summary.json");
  report::BackendRow& row = run->row;
  row.c2c_mean_m = io::NumberAt(summary, "c2c.mean_m");
  row.c2c_std_m = io::NumberAt(summary, "c2c.std_m");
  row.ms_per_scan_median = io::NumberAt(summary, "ms_per_scan_median");
  row.ms_per_scan_p99 = io::NumberAt(summary, "ms_per_scan_p99");
  row.cpu_ms_per_scan_median = io::NumberAt(summary, "cpu_ms_per_scan_median");
  row.scans = io::NumberAt(summary, "scans_processed");
  row.peak_memory_mb = io::NumberAt(io::ReadJsonFile(run->dir + "/process.json"), "peak_memory_mb");
  run->trajectory = io::ReadTum(run->dir + "/trajectory.tum");
  if (!request.ground_truth.empty()) {
    run->ate = EvaluateTrajectory(run->trajectory, request.ground_truth, request.rpe_delta_m, &row);
    // The live states beside the finalized ones: a smoother earns its cost where they differ.
    const std::string live_path = run->dir + "/trajectory_live.tum";
    if (std::filesystem::exists(live_path)) {
      const evaluation::AteResult live = evaluation::ComputeAte(
          ToTimed(io::ReadTum(live_path)), ToTimed(io::ReadTum(request.ground_truth)), {});
      if (live.ok) row.ate_live_rmse_m = live.rmse_m;
    }
  }
}

BackendRun RunOne(const BackendRunsRequest& request, const std::string& backend) {
  BackendRun run;
  run.row.backend = backend;
  run.dir = request.out_dir + "/" + backend;
  std::filesystem::remove(run.dir + "/error.txt");
  std::string error;
  const int status = RunChild(ChildArguments(request, backend), &error);
  if (status != 0) {
    run.row.status = report::RowStatus::kFailed;
    const std::string reason = FirstLine(run.dir + "/error.txt");
    run.row.note = !reason.empty() ? reason
                   : status < 0    ? error
                                   : "exit status " + std::to_string(status);
    return run;
  }
  try {
    ReadChildOutputs(request, &run);
  } catch (const std::exception& e) {
    run.row.status = report::RowStatus::kFailed;
    run.row.note = std::string("reading the run's outputs: ") + e.what();
  }
  return run;
}

}  // namespace

const std::vector<std::string>& AllBackends() {
  static const std::vector<std::string> kBackends{"ieskf", "sliding_window"};
  return kBackends;
}

evaluation::AteResult EvaluateTrajectory(const std::vector<io::StampedPose>& trajectory,
                                         const std::string& ground_truth, double rpe_delta_m,
                                         report::BackendRow* row) {
  const auto estimate = ToTimed(trajectory);
  const auto truth = ToTimed(io::ReadTum(ground_truth));
  evaluation::AteOptions ate_options;  // SE(3) Umeyama: the map frame is not the truth's
  evaluation::AteResult ate = evaluation::ComputeAte(estimate, truth, ate_options);
  if (ate.ok) row->ate_rmse_m = ate.rmse_m;
  evaluation::RpeOptions rpe_options;
  rpe_options.unit = evaluation::DeltaUnit::kMeters;
  rpe_options.delta = rpe_delta_m;
  const evaluation::RpeResult rpe = evaluation::ComputeRpe(estimate, truth, rpe_options);
  if (rpe.ok) row->rpe_rmse_m = rpe.rmse_m;
  if (!ate.ok) row->note = "ATE: " + ate.message;
  return ate;
}

std::vector<BackendRun> RunBackends(const BackendRunsRequest& request) {
  if (request.log.empty() || request.config_path.empty() || request.out_dir.empty()) {
    throw std::invalid_argument(
        "a back-end comparison needs a log, a configuration and an "
        "output folder");
  }
  if (!request.prior_map.empty()) localization::ParsePoseGuess(request.guess);  // fail early
  std::vector<BackendRun> runs;
  for (const std::string& backend : request.backends) runs.push_back(RunOne(request, backend));
  return runs;
}

void RunBackendHere(const BackendRunsRequest& request, const std::string& backend) {
  const std::string dir = request.out_dir + "/" + backend;
  try {
    run::RunRequest run;
    run.log = request.log;
    run.config = config::LoadRunConfig(request.config_path);
    if (!estimation::ParseBackend(backend, &run.config.pipeline.estimator.backend)) {
      throw std::invalid_argument("unknown back-end '" + backend + "'");
    }
    run.prior_map = request.prior_map;
    if (!request.prior_map.empty())
      run.guess_world_imu = localization::ParsePoseGuess(request.guess);
    run.out_dir = dir;
    run.label = backend;
    run::RunLog(run);
    io::Json process = io::Json::object();
    process["peak_memory_mb"] = OwnPeakMemoryMb();
    process["source"] = "VmHWM of this back-end's own process (/proc/self/status)";
    io::WriteJsonFile(dir + "/process.json", process);
  } catch (const std::exception& e) {
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/error.txt") << e.what() << '\n';
    throw;
  }
}

}  // namespace hylo::cli
