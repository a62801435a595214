#pragma once
// A global localization attempt of the search while moving, off the scan thread when asked. A
// search accumulates scans for seconds before it places them in the map, and one attempt costs
// a second or more of CPU: run on the scan thread it stalls tracking in the provisional frame
// (a live vehicle's scans queue up and are dropped). On a worker thread, at a lower priority
// than the scan thread, one at a time, the scan thread polls for the verdict and applies it
// through the odometry it kept meanwhile (see LocalizationSupervisor::Search). A log read from
// a file runs its attempts on the caller's thread instead: the same result on every run,
// whatever the machine's load.
//
// The map the attempt reads must not change while it runs: the caller keeps it read-only
// (a searching pipeline adds nothing to its map) and destroys this object, which waits for the
// attempt, before it changes the map.

#include <Eigen/Geometry>
#include <future>
#include <optional>

#include "hylo/common/point_types.h"
#include "hylo/localization/attempt_cloud.h"
#include "hylo/localization/global_search.h"
#include "hylo/localization/icp_initializer.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::localization {

/// One attempt and where the search frame had the vehicle when its cloud was taken.
struct SearchAttempt {
  /// Set: the attempt fits the cloud around this pose alone (where the vehicle was when it
  /// was lost) instead of searching the whole map; `result` is then accepted with that fit,
  /// or not, and carries it as its refinement.
  std::optional<Eigen::Isometry3d> T_map_imu_guess;
  GlobalLocalizationResult result;
  bool from_recent = false;  ///< placed by the last scans alone
  Eigen::Isometry3d T_search_imu = Eigen::Isometry3d::Identity();  ///< at the attempt's scan
  int64_t t_ns = 0;                                                ///< that scan's time, ns
  /// An accepted attempt: the last scans alone registered around its pose (plane steps
  /// included), at the attempt's scan; its pose is the one to keep when accepted.
  IcpInitializerResult recent_refinement;
  std::size_t points = 0;                                          ///< of the attempt's cloud
  double distance_m = 0.0;  ///< the search's travel by then, m
  int scans = 0;            ///< the search's scans by then
  int attempt = 0;          ///< 1, 2, ... within the search
};

class BackgroundSearch {
 public:
  /// `search`, `refiner`, `around_guess` and `map` must outlive this object. `around_guess`:
  /// the initializer for an attempt around a guess (one sweep). `on_worker`: attempts run on a
  /// worker thread; false: on the caller's, each finished when Start returns.
  BackgroundSearch(const GlobalSearch& search, const IcpInitializer& refiner,
                   const IcpInitializer& around_guess, const registration::NeighborSearch& map,
                   bool on_worker)
      : search_(search),
        refiner_(refiner),
        around_guess_(around_guess),
        map_(map),
        on_worker_(on_worker) {}
  /// Waits for an attempt still running.
  ~BackgroundSearch() { Wait(); }
  BackgroundSearch(const BackgroundSearch&) = delete;
  BackgroundSearch& operator=(const BackgroundSearch&) = delete;

  /// Starts an attempt on `clouds.accumulated` (moved where the attempt runs into the IMU
  /// frame at `attempt.T_search_imu`, once the future is ready) levelled by `R_level_imu`;
  /// `attempt` carries its bookkeeping. With `attempt.T_map_imu_guess` the cloud is only fitted
  /// around that pose (`around_guess`), nothing else is tried. Otherwise, when that cloud
  /// places nothing, `clouds.recent` (the last scans alone, same frame) is tried: the
  /// accumulated cloud is the more telling one while the provisional odometry holds, the
  /// recent scans carry little of its drift when it does not. An accepted place is refined on
  /// the recent scans (the refiner's ICP), so that the scan thread only composes the verdict
  /// with the odometry since the attempt's scan. False while an attempt runs or its verdict
  /// is not taken.
  bool Start(std::shared_future<AttemptClouds> clouds, const Eigen::Matrix3d& R_level_imu,
             SearchAttempt attempt);
  /// True while an attempt runs.
  bool Busy() const;
  /// The finished attempt, once; nothing while it runs or when none was started.
  std::optional<SearchAttempt> TakeFinished();

 private:
  // The attempt: the accumulated cloud, then the recent scans when it places nothing.
  SearchAttempt Run(const AttemptClouds& clouds, const Eigen::Matrix3d& R_level_imu,
                    SearchAttempt attempt) const;
  void Wait();

  const GlobalSearch& search_;
  const IcpInitializer& refiner_;
  const IcpInitializer& around_guess_;
  const registration::NeighborSearch& map_;
  const bool on_worker_;
  std::future<SearchAttempt> running_;     // on the worker
  std::optional<SearchAttempt> finished_;  // on the caller's thread
};

}  // namespace hylo::localization
