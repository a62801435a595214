#include "hylo/localization/background_search.h"

#include <chrono>
#include <utility>

#include "thread_niceness.h"

namespace hylo::localization {
namespace {

// Below the scan thread and the search's accumulation (moving_search.cpp): on a loaded
// computer the tracking keeps its share of the CPU and the attempt takes what is left.
constexpr int kAttemptNicenessBelowScanThread = 10;

}  // namespace

SearchAttempt BackgroundSearch::Run(const AttemptClouds& clouds, const Eigen::Matrix3d& R_level_imu,
                                    SearchAttempt attempt) const {
  const PointCloud cloud_imu = clouds.accumulated.Resolve();
  const PointCloud recent_imu = clouds.recent.Resolve();
  attempt.points = cloud_imu.size();
  if (attempt.T_map_imu_guess) {
    const IcpInitializerResult fit =
        around_guess_.Initialize(cloud_imu, map_, *attempt.T_map_imu_guess);
    attempt.result.status = fit.accepted ? GlobalStatus::kAccepted : GlobalStatus::kNotFound;
    attempt.result.T_map_imu = fit.T_map_imu;
    attempt.result.refinement = fit;
    attempt.result.message = fit.message;
    return attempt;
  }
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

bool BackgroundSearch::Start(std::shared_future<AttemptClouds> clouds,
                             const Eigen::Matrix3d& R_level_imu, SearchAttempt attempt) {
  if (Busy() || finished_) return false;
  if (!on_worker_) {
    finished_ = Run(clouds.get(), R_level_imu, std::move(attempt));
    return true;
  }
  const int scan_thread_niceness = ThisThreadsNiceness();
  running_ = std::async(std::launch::async, [this, clouds = std::move(clouds), R_level_imu,
                                             attempt = std::move(attempt), scan_thread_niceness]() {
    LowerThisThreadsPriority(scan_thread_niceness, kAttemptNicenessBelowScanThread);
    return Run(clouds.get(), R_level_imu, attempt);
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
