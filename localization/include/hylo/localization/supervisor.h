#pragma once
// Localization in a prior map, for every back-end alike (Alamanos et al., Sec. III, and
// localization.h): the ICP start from the static scans, the scans' health, loss and
// relocalization, the hybrid start of map updates, the REP-105 odom frame and the events of a
// run. The pipeline owns one when it localizes (SetInitialGuess, with or without a guess) and
// asks it at three moments: while starting (AddStaticScan, Start), after each update
// (Supervise), and before adding a scan to the map (MapUpdateAllowed).

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/common/sensor_data.h"
#include "hylo/estimation/estimator.h"
#include "hylo/estimation/imu_initializer.h"
#include "hylo/estimation/initial_uncertainty.h"
#include "hylo/localization/localization.h"
#include "hylo/localization/moving_search.h"
#include "hylo/localization/background_search.h"
#include "hylo/localization/global_search.h"
#include "hylo/localization/icp_initializer.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::localization {

class LocalizationSupervisor {
 public:
  /// `T_map_imu_guess`: the start guess, or none (a global start). `global_search`: the
  /// search of the whole prior map (available or why not), owned by the caller and outliving
  /// this. `search_map` and
  /// `search_planes`: the run's map and plane settings, for the scratch map of a search while
  /// moving (moving_search.h).
  LocalizationSupervisor(const LocalizationOptions& options, const estimation::InitialUncertainty& uncertainty,
                         const std::optional<Eigen::Isometry3d>& T_map_imu_guess,
                         const GlobalSearch* global_search,
                         const mapping::MapManagerOptions& search_map,
                         const registration::PlaneMatcherOptions& search_planes);

  /// Relocalize around `T_map_imu_guess` with the next scan (e.g. ROS /initialpose); before
  /// the start it replaces the initial guess.
  void RequestRelocalization(const Eigen::Isometry3d& T_map_imu_guess);
  /// Forget the pose and search the whole map (e.g. the robot was carried): before the start
  /// the guess is dropped; after it, from the next scan on, the vehicle searches while moving
  /// (no pose is reported until the global localizer accepts one). False with *why when there
  /// is no global map to search.
  bool RequestGlobalLocalization(std::string* why);

  // --- the start ---
  /// Adds one static scan (IMU frame, m) whose IMU data ends at `imu_end_t_ns` (0: none).
  void AddStaticScan(const PointCloud& points_imu, int64_t imu_end_t_ns);
  int static_scans() const { return static_.scans; }
  /// Registers the static scans to `map` and, when the initializer accepts a pose, starts
  /// `estimator` there. `start` carries time (the last static IMU stamp is used when there is
  /// one), biases, gravity and extrinsic; with `gravity_known` its roll and pitch (from the IMU
  /// at rest) replace the guess's. Without a guess, or when the guess is rejected, the global
  /// localizer searches the whole map (global_enabled). False with *why when no pose was
  /// accepted (rejected, ambiguous or not found: the reason says which); when the global
  /// localizer ran and options.search is enabled, searching() is then true and `estimator`
  /// runs in the search frame (see Search). With options.search.background the whole-map
  /// search is not made here: searching() is true and its first attempt, on the static scans,
  /// runs beside the scan path from the next scan on.
  bool Start(estimation::NavState start, bool gravity_known, const registration::NeighborSearch& map,
             estimation::Estimator* estimator, std::string* why);

  /// The log starts while the vehicle moves: no static scans to start from. `estimator`
  /// starts at `x` (attitude from the IMU, position zero) with covariance `P` in the search
  /// frame, and the vehicle searches while it moves from `points_imu` (one scan); `reason`
  /// says what showed the motion. False with *why when searching while moving is off.
  bool StartMoving(const estimation::NavState& x, const estimation::StateCovariance& P,
                   const PointCloud& points_imu, const std::string& reason,
                   estimation::Estimator* estimator, std::string* why);

  // --- searching while moving (moving_search.h) ---
  /// True while no pose is known and the estimator runs in the provisional search frame,
  /// registered against search_matcher() instead of the prior.
  bool searching() const { return search_ != nullptr; }
  const registration::PlaneMatcher& search_matcher() const { return search_->matcher(); }
  enum class SearchStep { kSearching, kLocalized, kGaveUp };
  /// After an update in the search frame: accumulates the scan (`sweep_imu` makes the whole
  /// deskewed scan in the IMU frame at the estimator's state, off the scan path with
  /// options.search.background; `map_points_search`, the points odometry adds to its map,
  /// search frame, empty when the update failed) and, when due, tries the global localizer
  /// on the longer cloud against `map` (the prior). kLocalized:
  /// `estimator` was started again at the accepted pose in the map. kGaveUp: max_distance_m
  /// travelled, the reason in *why.
  SearchStep Search(std::function<PointCloud()> sweep_imu, const PointCloud& map_points_search,
                    const registration::NeighborSearch& map, estimation::Estimator* estimator,
                    std::string* why);

  // --- every scan after the start ---
  /// Judges the scan that ended at `t_ns` (live state `state`) by its `health`, counts bad
  /// scans, declares the vehicle lost, and relocalizes on request (around the requested pose)
  /// or while lost (around the current pose, then over the whole map: a kidnapped vehicle is
  /// found again). True when an accepted relocalization started `estimator` again at the
  /// accepted pose (the caller reports the estimator's new state). `sweep_imu` gives the whole
  /// scan in the IMU frame at its end (asked for only to relocalize).
  bool Supervise(int64_t t_ns, const ScanHealth& health, const estimation::NavState& state,
                 const std::function<PointCloud()>& sweep_imu,
                 const registration::NeighborSearch& map, estimation::Estimator* estimator);
  /// Hybrid mode: whether the scan that ended at `t_ns` (state `state`, its update applied or
  /// not, its `health`) may extend the map.
  bool MapUpdateAllowed(int64_t t_ns, bool update_applied, const ScanHealth& health,
                        const estimation::NavState& state);
  /// Whether a scan ending at `t_ns` would extend the map if it fits (MapUpdateAllowed's
  /// answer for a good scan, without its side effects): hybrid mode once started, odometry
  /// off a tiled prior; never while lost.
  bool ScansExtendMap(int64_t t_ns) const;
  /// Whether the vehicle is on the prior's tiles (a tiled prior; always true otherwise), told
  /// before each scan. Off them there is no prior to localize in: loss and relocalization are
  /// suspended and registered scans extend the run's map (odometry mode) until it comes back;
  /// both moments are events. `T_map_imu`: the pose the event records.
  void SetOnMap(bool on_map, int64_t t_ns, const Eigen::Isometry3d& T_map_imu);
  bool on_map() const { return on_map_; }

  /// The scan ending at `t_ns` comes after `gap_s` without data: the state propagated through
  /// the gap is not trusted until a fit of the scan near it (the initializer's, as a
  /// relocalization) confirms it; its health alone does not.
  /// `imu_too`: the IMU was silent as well and the estimator was restarted at the gap's start
  /// (the event says so); the vehicle may then be anywhere it could have driven, and the whole
  /// map is searched (when it can be) without trusting a fit near the gap's start. Nothing
  /// before the start, while searching or off the prior.
  void DataGap(int64_t t_ns, double gap_s, bool imu_too, const Eigen::Isometry3d& T_map_imu);
  bool lost() const { return lost_; }
  /// True once a start pose was accepted (a later search is a relocalization).
  bool started() const { return started_; }
  /// map → odom (REP-105): relocalization jumps go here, so odom → imu stays continuous.
  const lie::SE3d& T_map_odom() const { return T_map_odom_; }
  const std::vector<LocalizationEvent>& events() const { return events_; }
  std::size_t scans_initializer() const { return scans_initializer_; }
  std::size_t scans_bad_health() const { return scans_bad_health_; }

 private:
  struct StaticScans {
    PointCloud points_imu;  // accumulated static scans, IMU frame
    int scans = 0;
    int64_t imu_end_t_ns = 0;  // last IMU stamp of the static scans
  };

  // The global localizer on the static scans; `icp` receives the accepted pose's refinement.
  // Returns its verdict, one line.
  std::string StartGlobally(const estimation::NavState& start, bool gravity_known,
                            const registration::NeighborSearch& map,
                            IcpInitializerResult* icp) const;
  // Searching while moving is possible: enabled, and a global map to search.
  bool CanSearch() const { return options_.search.enabled && global_->available(); }
  // Starts searching while moving from `x` (search frame = the estimator's frame), seeded
  // with `points_imu`; `reason` says why there is no pose. The first attempt is made after
  // `first_attempt_scans` scans (0: once the vehicle has moved retry_m).
  void BeginSearch(const estimation::NavState& x, const PointCloud& points_imu, bool is_start,
                   int first_attempt_scans, const std::string& reason);
  // The estimator restarted where it is with a moving start's uncertainty and no velocity,
  // for a search.
  void RestartForSearch(estimation::Estimator* estimator) const;
  // The search's attempts (created on first use, against `map`).
  BackgroundSearch& Background(const registration::NeighborSearch& map);
  // The search's first attempt when the vehicle was lost: `sweep_imu` fitted around
  // `T_map_imu_guess`, the pose where it was lost (= the search frame's origin then).
  void StartAttempt(const PointCloud& sweep_imu, const Eigen::Isometry3d& T_map_imu_guess,
                    const registration::NeighborSearch& map);
  // Concludes a finished attempt, if any. True when the search ended with a pose.
  bool TakeFinishedAttempt(estimation::Estimator* estimator);
  // A finished global attempt: accepted, its place (refined on the last scans) is carried to
  // now by the search frame's odometry; otherwise an event says why. True when the search
  // ended.
  bool Conclude(const SearchAttempt& attempt, estimation::Estimator* estimator);
  // The same for the fit around the last pose; rejected, the estimator restarts for the
  // whole-map search (RestartForSearch).
  bool ConcludeNearGuess(const SearchAttempt& attempt, estimation::Estimator* estimator);
  // The search found the vehicle at `T_map_imu`: the estimator goes on in the map.
  void EndSearch(const Eigen::Isometry3d& T_map_imu, estimation::Estimator* estimator,
                 const std::string& verdict, const IcpInitializerResult& icp);
  // The initializer around `T_map_imu_guess`; when it fails and `allow_global`, the global
  // localizer on the sweep.
  bool Relocalize(const PointCloud& sweep_imu, const registration::NeighborSearch& map,
                  const Eigen::Isometry3d& T_map_imu_guess, bool allow_global,
                  estimation::Estimator* estimator);
  void AddEvent(LocalizationEvent::Kind kind, int64_t t_ns, const std::string& message,
                const Eigen::Isometry3d& T_map_imu,
                const IcpInitializerResult* icp = nullptr);

  LocalizationOptions options_;
  estimation::InitialUncertainty uncertainty_;
  IcpInitializer icp_initializer_;
  // The same without point-to-plane steps, for one sweep of a moving vehicle: on so few points
  // the steps slid a relocalization 13 cm along the site's weakly constrained directions,
  // where the point-to-point ICP alone stayed within millimetres.
  IcpInitializer sweep_initializer_;
  const GlobalSearch* global_;  // not owned
  std::optional<Eigen::Isometry3d> guess_;     // T_map_imu at the start; none: global start
  StaticScans static_;
  std::optional<Eigen::Isometry3d> relocalize_request_;  // T_map_imu
  bool global_request_ = false;                          // search from the next scan on
  mapping::MapManagerOptions search_map_;
  registration::PlaneMatcherOptions search_planes_;
  std::unique_ptr<MovingSearch> search_;  // non-null while searching
  std::unique_ptr<BackgroundSearch> background_;  // the search's global attempts
  std::string last_attempt_;        // the last attempt's verdict, for a search that gives up
  bool search_is_start_ = false;          // the search began at the start (not on request)
  int search_first_attempt_scans_ = 0;    // see BeginSearch
  int64_t search_t_ns_ = 0;               // when the search began
  // Lost after a gap in the data (DataGap): health cannot clear the loss; the fit near the
  // last pose comes first, or (a gap without IMU) the whole map is searched at once.
  enum class AfterGap { kNone, kFitFirst, kSearchAtOnce };
  AfterGap after_gap_ = AfterGap::kNone;
  int bad_scans_in_row_ = 0;
  int scans_until_retry_ = 0;
  bool lost_ = false;
  bool started_ = false;
  int64_t start_t_ns_ = 0;
  bool hybrid_started_ = false;
  bool on_map_ = true;
  lie::SE3d T_map_odom_;
  std::vector<LocalizationEvent> events_;
  std::size_t scans_initializer_ = 0;  // static scans and relocalization attempts
  std::size_t scans_bad_health_ = 0;
};

/// True when the IMU samples `imu` say the vehicle is still at rest, judged with the static
/// initialisation's thresholds against its gyro bias (`imu_start`) and `gravity_mps2`.
bool ImuAtRest(const std::vector<ImuSample>& imu, const estimation::NavState& imu_start,
               const estimation::ImuInitializerOptions& init, double gravity_mps2);

}  // namespace hylo::localization
