#include "hylo/localization/background_search.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <chrono>
#include <utility>

namespace hylo::localization {
namespace {

// Below the scan thread: on a loaded computer the tracking keeps its share of the CPU and the
// attempt takes what is left. Best effort: an unprivileged thread may only lower itself.
constexpr int kWorkerNiceness = 10;

void LowerThisThreadsPriority() {
  const auto tid = static_cast<id_t>(syscall(SYS_gettid));
  setpriority(PRIO_PROCESS, tid, kWorkerNiceness);
}

}  // namespace

SearchAttempt BackgroundSearch::Run(const PointCloud& cloud_imu, const PointCloud& recent_imu,
                                    const Eigen::Matrix3d& R_level_imu,
                                    SearchAttempt attempt) const {
  attempt.points = cloud_imu.size();
  attempt.result = search_.Localize(cloud_imu, R_level_imu, map_);
  if (attempt.result.status != GlobalStatus::kAccepted && !recent_imu.empty()) {
    GlobalLocalizationResult recent = search_.Localize(recent_imu, R_level_imu, map_);
    if (recent.status == GlobalStatus::kAccepted) {
      recent.elapsed_s += attempt.result.elapsed_s;
      attempt.result = std::move(recent);
      attempt.from_recent = true;
      attempt.points = recent_imu.size();
    } else {
      attempt.result.message += "; last scans alone: " + recent.message;
      attempt.result.elapsed_s += recent.elapsed_s;
    }
  }
  if (attempt.result.status == GlobalStatus::kAccepted && !recent_imu.empty()) {
    attempt.recent_refinement = refiner_.Initialize(recent_imu, map_, attempt.result.T_map_imu);
  }
  return attempt;
}

bool BackgroundSearch::Start(PointCloud cloud_imu, PointCloud recent_imu,
                             const Eigen::Matrix3d& R_level_imu, SearchAttempt attempt) {
  if (Busy() || finished_) return false;
  if (!on_worker_) {
    finished_ = Run(cloud_imu, recent_imu, R_level_imu, std::move(attempt));
    return true;
  }
  running_ = std::async(std::launch::async,
                        [this, cloud = std::move(cloud_imu), recent = std::move(recent_imu),
                         R_level_imu, attempt = std::move(attempt)]() {
                          LowerThisThreadsPriority();
                          return Run(cloud, recent, R_level_imu, attempt);
                        });
  return true;
}

bool BackgroundSearch::Busy() const {
  return running_.valid() &&
         running_.wait_for(std::chrono::seconds(0)) != std::future_status::ready;
}

std::optional<SearchAttempt> BackgroundSearch::TakeFinished() {
  if (finished_) {
    std::optional<SearchAttempt> done = std::move(finished_);
    finished_.reset();
    return done;
  }
  if (!running_.valid() || Busy()) return std::nullopt;
  return running_.get();
}

void BackgroundSearch::Wait() {
  if (running_.valid()) running_.wait();
}

}  // namespace hylo::localization
