#pragma once
// A global localization attempt off the scan thread. A search while moving accumulates scans
// for seconds before it places them in the map, and one attempt costs a second or more of
// CPU: run on the scan thread it stalls tracking in the provisional frame (a live vehicle's
// scans queue up and are dropped). Here an attempt runs on a worker thread, at a lower
// priority than the scan thread, one at a time; the scan thread polls for the verdict and
// applies it through the odometry it kept meanwhile (see LocalizationSupervisor::Search).
//
// The map the attempt reads must not change while it runs: the caller keeps it read-only
// (a searching pipeline adds nothing to its map) and waits for the attempt before it does.

#include <Eigen/Geometry>
#include <future>
#include <optional>

#include "hylo/common/point_types.h"
#include "hylo/localization/global_search.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::localization {

/// One attempt and where the search frame had the vehicle when its cloud was taken.
struct SearchAttempt {
  GlobalLocalizationResult result;
  bool from_recent = false;  ///< placed by the last scans alone
  Eigen::Isometry3d T_search_imu = Eigen::Isometry3d::Identity();  ///< at the attempt's scan
  int64_t t_ns = 0;                                                ///< that scan's time, ns
  std::size_t points = 0;                                          ///< of the attempt's cloud
  double distance_m = 0.0;  ///< the search's travel by then, m
  int scans = 0;            ///< the search's scans by then
  int attempt = 0;          ///< 1, 2, ... within the search
};

class BackgroundSearch {
 public:
  /// `search` and `map` must outlive this object.
  BackgroundSearch(const GlobalSearch& search, const registration::NeighborSearch& map)
      : search_(search), map_(map) {}
  /// Waits for an attempt still running.
  ~BackgroundSearch() { Wait(); }
  BackgroundSearch(const BackgroundSearch&) = delete;
  BackgroundSearch& operator=(const BackgroundSearch&) = delete;

  /// Starts an attempt on `cloud_imu` (IMU frame at `attempt.T_search_imu`) levelled by
  /// `R_level_imu`; `attempt` carries its bookkeeping. When that cloud places nothing,
  /// `recent_imu` (the last scans alone, same frame) is tried: the accumulated cloud is the
  /// more telling one while the provisional odometry holds, the recent scans carry little of
  /// its drift when it does not. False when an attempt is still running.
  bool Start(PointCloud cloud_imu, PointCloud recent_imu, const Eigen::Matrix3d& R_level_imu,
             SearchAttempt attempt);
  /// True while an attempt runs.
  bool Busy() const;
  /// The finished attempt, once; nothing while it runs or when none was started.
  std::optional<SearchAttempt> TakeFinished();
  /// Blocks until an attempt in flight has finished (its verdict stays to be taken).
  void Wait();

 private:
  const GlobalSearch& search_;
  const registration::NeighborSearch& map_;
  std::future<SearchAttempt> running_;
};

}  // namespace hylo::localization
