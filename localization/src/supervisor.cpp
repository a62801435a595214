// Localization in a prior map: the ICP start, health and loss, relocalization, hybrid mode
// (supervisor.h).
#include "hylo/localization/supervisor.h"

#include <cmath>
#include <sstream>

#include "hylo/common/time.h"
#include "hylo/lie/isometry.h"

namespace hylo::localization {
namespace {

double YawOf(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

IcpInitializerOptions WithoutPlaneSteps(IcpInitializerOptions icp) {
  icp.plane_refine_iterations = 0;
  return icp;
}

}  // namespace

bool ImuAtRest(const std::vector<ImuSample>& imu, const estimation::NavState& imu_start,
               const estimation::ImuInitializerOptions& init, double gravity_mps2) {
  if (imu.empty()) return false;
  Eigen::Vector3d gyro_mean = Eigen::Vector3d::Zero();
  double accel_norm_mean = 0.0;
  for (const ImuSample& s : imu) {
    gyro_mean += s.gyro_imu;
    accel_norm_mean += s.accel_imu.norm();
  }
  const double n = static_cast<double>(imu.size());
  gyro_mean /= n;
  accel_norm_mean /= n;
  return (gyro_mean - imu_start.gyro_bias).norm() < init.max_gyro_mean_radps &&
         std::abs(accel_norm_mean - gravity_mps2) < init.gravity_tolerance_mps2;
}

LocalizationSupervisor::LocalizationSupervisor(
    const LocalizationOptions& options, const estimation::InitialUncertainty& uncertainty,
    const std::optional<Eigen::Isometry3d>& T_map_imu_guess, const GlobalSearch* global_search,
    const mapping::MapManagerOptions& search_map,
    const registration::PlaneMatcherOptions& search_planes)
    : options_(options),
      uncertainty_(uncertainty),
      icp_initializer_(options.icp),
      sweep_initializer_(WithoutPlaneSteps(options.icp)),
      global_(global_search),
      guess_(T_map_imu_guess),
      search_map_(search_map),
      search_planes_(search_planes) {}

void LocalizationSupervisor::RequestRelocalization(const Eigen::Isometry3d& T_map_imu_guess) {
  if (!started_ && !searching()) {
    guess_ = T_map_imu_guess;  // the start uses it
    return;
  }
  relocalize_request_ = T_map_imu_guess;
}

void LocalizationSupervisor::AddStaticScan(const PointCloud& points_imu, int64_t imu_end_t_ns) {
  static_.points_imu.insert(static_.points_imu.end(), points_imu.begin(), points_imu.end());
  if (imu_end_t_ns != 0) static_.imu_end_t_ns = imu_end_t_ns;
  ++static_.scans;
  ++scans_initializer_;
}

bool LocalizationSupervisor::Start(estimation::NavState start, bool gravity_known,
                                   const registration::NeighborSearch& map,
                                   estimation::Estimator* estimator, std::string* why) {
  std::optional<Eigen::Isometry3d> guess = guess_;
  if (gravity_known) {
    // Roll and pitch from gravity, yaw and position from the user's guess.
    const Eigen::Vector3d up_imu = start.R_map_imu.Matrix().transpose() * Eigen::Vector3d::UnitZ();
    if (guess) {
      guess = GuessFromGravity(guess->translation(), YawOf(guess->rotation()), up_imu);
    }
    start.t_ns = static_.imu_end_t_ns;
  }
  IcpInitializerResult icp;
  std::string verdict;
  if (guess) {
    icp = icp_initializer_.Initialize(static_.points_imu, map, *guess);
    verdict = icp.message;
  }
  // A live vehicle's scans must not wait behind a global search of a second or more: with
  // attempts beside the scan path, the start searches as a search while moving does, from the
  // static scans, its first attempt at once.
  const bool search_beside = options_.search.background && CanSearch();
  if (!icp.accepted && global_->enabled()) {
    verdict = (guess ? "guess rejected (" + verdict + "), then " : std::string()) +
              "global localization " +
              (search_beside ? std::string("beside the scan path")
                             : StartGlobally(start, gravity_known, map, &icp));
  } else if (!guess) {
    verdict = "no guess and " + global_->why_unavailable();
  }
  const int scans = static_.scans;
  const PointCloud static_points_imu = std::move(static_.points_imu);
  static_ = StaticScans();
  if (!icp.accepted && CanSearch()) {
    // Ambiguous or not found: no pose is picked; the vehicle searches while it moves.
    start.p_map_imu.setZero();
    start.v_map_imu.setZero();
    estimator->Initialize(start, uncertainty_.SlamCovariance());
    BeginSearch(start, static_points_imu, /*is_start=*/true,
                /*first_attempt_scans=*/search_beside ? 1 : 0, verdict);
    *why = "no start pose yet (" + std::to_string(scans) + " static scans): " + verdict;
    return false;
  }
  if (!icp.accepted) {
    *why = "no start pose (" + std::to_string(scans) + " static scans): " + verdict;
    AddEvent(LocalizationEvent::Kind::kInitializationFailed, start.t_ns, verdict,
             Eigen::Isometry3d::Identity(), &icp);
    return false;
  }
  const lie::SE3d T_map_imu = lie::FromIsometry(icp.T_map_imu);
  start.R_map_imu = T_map_imu.so3();
  start.p_map_imu = T_map_imu.translation();
  start.v_map_imu.setZero();
  estimator->Initialize(start, uncertainty_.LocalizedCovariance());
  start_t_ns_ = start.t_ns;
  started_ = true;
  AddEvent(LocalizationEvent::Kind::kInitialized, start.t_ns, verdict, icp.T_map_imu, &icp);
  return true;
}

std::string LocalizationSupervisor::StartGlobally(const estimation::NavState& start,
                                                  bool gravity_known,
                                                  const registration::NeighborSearch& map,
                                                  IcpInitializerResult* icp) const {
  if (!global_->available()) return "unavailable: " + global_->why_unavailable();
  // With an IMU at rest, gravity levels the scans; without one a ground vehicle is taken to
  // start near level (the refinement then corrects a few degrees of tilt).
  const Eigen::Matrix3d R_level =
      gravity_known ? LevellingRotation(start.R_map_imu.Matrix()) : Eigen::Matrix3d::Identity();
  const GlobalLocalizationResult r = global_->Localize(static_.points_imu, R_level, map);
  if (r.status == GlobalStatus::kAccepted) *icp = r.refinement;
  std::ostringstream os;
  os << r.message << " (" << r.stats.nodes_scored << " search nodes, " << r.elapsed_s << " s CPU)";
  return os.str();
}

void LocalizationSupervisor::SetOnMap(bool on_map, int64_t t_ns,
                                      const Eigen::Isometry3d& T_map_imu) {
  if (on_map == on_map_ || !started_) return;
  on_map_ = on_map;
  if (!on_map) {
    bad_scans_in_row_ = 0;
    lost_ = false;
  }
  AddEvent(on_map ? LocalizationEvent::Kind::kReenteredMap : LocalizationEvent::Kind::kLeftMap,
           t_ns,
           on_map ? "back on the prior map's tiles: localization in the prior again"
                  : "off the prior map's tiles: odometry only (scans extend the run's map) "
                    "until the vehicle comes back",
           T_map_imu);
}

void LocalizationSupervisor::DataGap(int64_t t_ns, double gap_s, bool imu_too,
                                     const Eigen::Isometry3d& T_map_imu) {
  if (!started_ || searching() || !on_map_ || lost_) return;
  lost_ = true;
  scans_until_retry_ = 0;
  // The scan's health does not clear this loss: its update pulls a pose metres off part of
  // the way, and the inlier ratio then passes while the pose is still off. The initializer's
  // fit near the pose, whose gates are stricter, confirms or replaces it. Blind across the
  // gap, the vehicle may be anywhere it could drive meanwhile: a fit near where it was would
  // as readily be a look-alike bay as the place, and the whole map is searched instead,
  // where the global localizer can tell.
  after_gap_ = imu_too && CanSearch() ? AfterGap::kSearchAtOnce : AfterGap::kFitFirst;
  std::ostringstream os;
  os << "no data for " << gap_s << " s: ";
  if (after_gap_ == AfterGap::kSearchAtOnce) {
    os << "no IMU either, so the state restarts where the gap began (levelled by the "
          "accelerometer, velocity unknown) and the place is searched for over the whole map";
  } else {
    os << (imu_too ? "no IMU either: the state restarted where the gap began"
                   : "the pose propagated through the gap")
       << " is confirmed by a fit of the scan near it first";
  }
  AddEvent(LocalizationEvent::Kind::kLost, t_ns, os.str(), T_map_imu);
}

bool LocalizationSupervisor::Supervise(int64_t t_ns, const ScanHealth& health,
                                       const estimation::NavState& state,
                                       const std::function<PointCloud()>& sweep_imu,
                                       const registration::NeighborSearch& map,
                                       estimation::Estimator* estimator) {
  if (!on_map_) return false;  // no prior here to judge the scan by, or to relocalize in
  if (!health.good) ++scans_bad_health_;
  bad_scans_in_row_ = health.good ? 0 : bad_scans_in_row_ + 1;
  if (lost_ && health.good && after_gap_ == AfterGap::kNone) lost_ = false;
  if (!lost_ && bad_scans_in_row_ >= options_.lost_after_scans) {
    lost_ = true;
    scans_until_retry_ = 0;
    std::ostringstream os;
    os << bad_scans_in_row_ << " bad scans in a row (inlier ratio " << health.inlier_ratio << ", "
       << health.num_matches << " matches)";
    AddEvent(LocalizationEvent::Kind::kLost, t_ns, os.str(), lie::ToIsometry(state.T_map_imu()));
  }
  if (global_request_) {
    global_request_ = false;
    relocalize_request_.reset();
    // A standing vehicle tries once it has as many scans as a start.
    BeginSearch(estimator->state(), sweep_imu(), /*is_start=*/false, options_.init_scans,
                "global localization requested");
    return false;
  }
  std::optional<Eigen::Isometry3d> guess;
  guess.swap(relocalize_request_);
  if (guess) {
    // A user's request is judged as given; only a lost vehicle's search may go global.
    return Relocalize(sweep_imu(), map, *guess, /*allow_global=*/false, estimator);
  }
  if (!lost_ || scans_until_retry_-- > 0) return false;
  // Lost: first around where the vehicle was (a slip, a short gap). When that fails and
  // searching while moving is possible, the vehicle may be anywhere: odometry goes on in a
  // provisional frame and the accumulated scans, far more telling than one sweep, are placed
  // in the map (moving_search.h). Without it, the sweep alone is searched for over the whole
  // map, again every relocalize_retry_scans.
  const PointCloud sweep = sweep_imu();
  const Eigen::Isometry3d here = lie::ToIsometry(estimator->state().T_map_imu());
  const bool local_first = after_gap_ != AfterGap::kSearchAtOnce;
  after_gap_ = AfterGap::kNone;
  if (!CanSearch()) {
    if (Relocalize(sweep, map, here, /*allow_global=*/true, estimator)) return true;
    scans_until_retry_ = options_.relocalize_retry_scans;
    return false;
  }
  if (!local_first) {
    RestartForSearch(estimator);
    BeginSearch(estimator->state(), sweep, /*is_start=*/false, /*first_attempt_scans=*/1,
                "lost: no match near the last pose is tried after a gap without IMU");
    return false;
  }
  // The search begins at once, its frame where the vehicle was lost, so that the fit near the
  // last pose (an ICP on the sweep, up to seconds from a poor guess) is its first attempt and
  // runs where the search's attempts run: beside the scan path when they do. Until it fails
  // the state is kept as it is; then the first whole-map attempt follows on the next scan.
  BeginSearch(estimator->state(), sweep, /*is_start=*/false, /*first_attempt_scans=*/1,
              "lost: " + events_.back().message + "; first a fit near the last pose");
  StartAttempt(sweep, here, map);
  return TakeFinishedAttempt(estimator);
}

void LocalizationSupervisor::RestartForSearch(estimation::Estimator* estimator) const {
  // The state that lost the map (after a gap, a slip or a jump) is not trusted to carry the
  // provisional frame: its velocity and attitude start again as a moving start's, wide enough
  // for any ground vehicle, for the scans to correct.
  estimation::NavState restart = estimator->state();
  restart.v_map_imu.setZero();
  estimator->Initialize(restart, uncertainty_.MovingCovariance(restart));
}

bool LocalizationSupervisor::Relocalize(const PointCloud& sweep_imu,
                                        const registration::NeighborSearch& map,
                                        const Eigen::Isometry3d& T_map_imu_guess, bool allow_global,
                                        estimation::Estimator* estimator) {
  const estimation::NavState before = estimator->state();
  ++scans_initializer_;
  IcpInitializerResult icp = sweep_initializer_.Initialize(sweep_imu, map, T_map_imu_guess);
  std::string verdict = icp.message;
  if (!icp.accepted && allow_global && global_->available()) {
    // Not near the last pose (kidnapped, or lost for long): search the whole map, levelled
    // by the estimate's roll and pitch, which the IMU keeps while the position is lost.
    const GlobalLocalizationResult r =
        global_->Localize(sweep_imu, LevellingRotation(before.R_map_imu.Matrix()), map);
    if (r.status == GlobalStatus::kAccepted) icp = r.refinement;
    verdict = "around the last pose: " + verdict + "; global localization " + r.message;
  }
  if (!icp.accepted) {
    AddEvent(LocalizationEvent::Kind::kRelocalizationFailed, before.t_ns, verdict,
             lie::ToIsometry(before.T_map_imu()), &icp);
    return false;
  }
  estimation::NavState x = before;
  const lie::SE3d T_map_imu = lie::FromIsometry(icp.T_map_imu);
  x.R_map_imu = T_map_imu.so3();
  x.p_map_imu = T_map_imu.translation();
  x.v_map_imu = x.R_map_imu * (before.R_map_imu.Inverse() * before.v_map_imu);  // body velocity
  estimator->Initialize(x, uncertainty_.LocalizedCovariance());
  // REP-105: odom→imu stays continuous, the jump goes into map→odom.
  const lie::SE3d T_odom_imu_before = T_map_odom_.Inverse() * before.T_map_imu();
  T_map_odom_ = x.T_map_imu() * T_odom_imu_before.Inverse();
  bad_scans_in_row_ = 0;
  lost_ = false;
  after_gap_ = AfterGap::kNone;
  AddEvent(LocalizationEvent::Kind::kRelocalized, x.t_ns, verdict, icp.T_map_imu, &icp);
  return true;
}

bool LocalizationSupervisor::MapUpdateAllowed(int64_t t_ns, bool update_applied,
                                              const ScanHealth& health,
                                              const estimation::NavState& state) {
  if (!on_map_) return update_applied;  // odometry mode needs a map of its own
  const double after_s = options_.update_after_s;
  if (after_s < 0.0 || NanosToSeconds(t_ns - start_t_ns_) < after_s) return false;
  if (!hybrid_started_) {
    hybrid_started_ = true;
    AddEvent(LocalizationEvent::Kind::kHybridStarted, t_ns,
             "registered scans are added to the map from now on",
             lie::ToIsometry(state.T_map_imu()));
  }
  // Only scans that fit the map extend it: a scan registered while lost would corrupt it.
  return update_applied && health.good && !lost_;
}

bool LocalizationSupervisor::ScansExtendMap(int64_t t_ns) const {
  if (lost_) return false;
  if (!on_map_) return true;
  const double after_s = options_.update_after_s;
  return after_s >= 0.0 && NanosToSeconds(t_ns - start_t_ns_) >= after_s;
}

void LocalizationSupervisor::AddEvent(LocalizationEvent::Kind kind, int64_t t_ns,
                                      const std::string& message,
                                      const Eigen::Isometry3d& T_map_imu,
                                      const IcpInitializerResult* icp) {
  LocalizationEvent event;
  event.kind = kind;
  event.t_ns = t_ns;
  event.T_map_imu = T_map_imu;
  if (icp != nullptr) {
    event.fitness_m2 = icp->accepted ? icp->fitness_score_m2 : icp->best_fitness_score_m2;
    event.plane_fitness_m2 = icp->accepted ? icp->plane_fitness_m2 : icp->best_plane_fitness_m2;
    event.inlier_ratio = icp->accepted ? icp->inlier_ratio : icp->best_inlier_ratio;
  }
  event.message = message;
  events_.push_back(event);
}

}  // namespace hylo::localization
