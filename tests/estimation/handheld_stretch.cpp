#include "estimation/handheld_stretch.h"

#include <algorithm>
#include <cmath>

#include "hylo/logs/log_reader.h"
#include "hylo/logs/scan_folder.h"
#include "hylo/run/session.h"

namespace hylo::testing {

const std::vector<std::string>& HandheldStretches() {
  static const std::vector<std::string> stretches = {"balm_scans", "balm_scans_40_59",
                                                     "balm_scans_100_119"};
  return stretches;
}

std::vector<std::string> HandheldStretchDirs(const std::string& data_dir) {
  std::vector<std::string> dirs;
  for (const std::string& s : HandheldStretches()) dirs.push_back(data_dir + "/" + s);
  return dirs;
}

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double rank = std::ceil(q * static_cast<double>(values.size()));
  const std::size_t index = static_cast<std::size_t>(std::max(rank, 1.0)) - 1;
  return values[std::min(index, values.size() - 1)];
}

StretchRun RunStretch(const std::string& dir, const odometry::OdometryPipelineOptions& options,
                      int stride, std::size_t max_scans) {
  run::Session session(options, run::SessionKeeps{true, false});
  logs::LogReadOptions read;
  read.imu_topic.clear();
  auto log = logs::OpenLog(dir, read);
  logs::LogMessage message;
  StretchRun run;
  std::size_t seen = 0, fed = 0;
  while (log->Next(&message) && (max_scans == 0 || fed < max_scans)) {
    if (message.kind != logs::LogMessage::Kind::kScan) continue;
    if (seen++ % static_cast<std::size_t>(stride) != 0) continue;
    ++fed;
    session.AddScan(std::move(message.scan));
  }
  session.Finish();
  run.results = session.results();
  const std::vector<estimation::NavState>& finalized = session.finalized();

  // The trajectory a run writes (trajectory.tum): each scan's finalized state.
  std::vector<evaluation::TimedPose> estimate, reference;
  for (const estimation::NavState& x : finalized) {
    estimate.push_back({x.t_ns, Eigen::Isometry3d(x.T_map_lidar().Matrix())});
  }
  for (const odometry::ScanResult& r : run.results) {
    run.cpu_ms.push_back(r.cpu_ms);
    if (r.update.robust.attempts > 1) ++run.retried_scans;
    if (r.update.robust.attempts > 0 && !r.update.robust.passed) ++run.unchecked_scans;
    if (!r.update.applied) ++run.not_applied;
  }
  for (const io::StampedPose& p : logs::ReadScanFolderPoses(dir)) {
    reference.push_back({p.t_ns, p.T_world_body()});
  }
  run.scans = run.results.size();
  evaluation::AteOptions ate;
  ate.association.method = evaluation::Association::kNearest;
  run.ate = evaluation::ComputeAte(estimate, reference, ate);
  evaluation::RpeOptions rpe;
  rpe.association.method = evaluation::Association::kNearest;
  const evaluation::RpeResult step = evaluation::ComputeRpe(estimate, reference, rpe);
  run.worst_step_m = step.max_m;
  run.worst_step_deg = step.rotation_max_deg;
  return run;
}

}  // namespace hylo::testing
