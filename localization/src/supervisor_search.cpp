// The supervisor's side of searching while moving (moving_search.h): when a search begins,
// each attempt of the global localizer on the accumulated cloud, and the end of a search.
#include <optional>
#include <sstream>
#include <utility>

#include "hylo/lie/isometry.h"
#include "hylo/localization/supervisor.h"

namespace hylo::localization {

bool LocalizationSupervisor::RequestGlobalLocalization(std::string* why) {
  if (!global_->available()) {
    *why = "no global map: " + global_->why_unavailable();
    return false;
  }
  if (!started_ && !searching()) {
    guess_.reset();  // the start searches the whole map
    return true;
  }
  if (!searching()) global_request_ = true;
  return true;
}

bool LocalizationSupervisor::StartMoving(const estimation::NavState& x,
                                         const estimation::StateCovariance& P,
                                         const PointCloud& points_imu, const std::string& reason,
                                         estimation::Estimator* estimator, std::string* why) {
  if (!CanSearch()) {
    *why = "no start pose: " + reason + ", and a start on the move needs a search while moving (" +
           (options_.search.enabled ? global_->why_unavailable()
                                    : std::string("localization.search.enabled is false")) +
           ")";
    AddEvent(LocalizationEvent::Kind::kInitializationFailed, x.t_ns, *why,
             Eigen::Isometry3d::Identity());
    return false;
  }
  estimator->Initialize(x, P);
  BeginSearch(x, points_imu, /*is_start=*/true, /*first_attempt_scans=*/0, reason);
  return true;
}

void LocalizationSupervisor::BeginSearch(const estimation::NavState& x,
                                         const PointCloud& points_imu, bool is_start,
                                         int first_attempt_scans, const std::string& reason) {
  search_ = std::make_unique<MovingSearch>(options_.search, search_map_, search_planes_,
                                           options_.global.max_range_m, options_.init_scans,
                                           /*accumulate_on_worker=*/options_.search.background);
  search_->Begin(points_imu, lie::ToIsometry(x.T_map_imu()));
  search_is_start_ = is_start;
  search_first_attempt_scans_ = first_attempt_scans;
  search_t_ns_ = x.t_ns;
  lost_ = false;
  after_gap_ = AfterGap::kNone;
  bad_scans_in_row_ = 0;
  AddEvent(LocalizationEvent::Kind::kSearching, x.t_ns,
           reason + "; searching while the vehicle moves (no pose until one is accepted)",
           lie::ToIsometry(x.T_map_imu()));
}

LocalizationSupervisor::SearchStep LocalizationSupervisor::Search(
    std::function<PointCloud()> sweep_imu, const PointCloud& map_points_search,
    const registration::NeighborSearch& map, estimation::Estimator* estimator, std::string* why) {
  const estimation::NavState x = estimator->state();
  const Eigen::Isometry3d T_search_imu = lie::ToIsometry(x.T_map_imu());
  const bool due = search_->Add(std::move(sweep_imu), map_points_search, T_search_imu,
                                search_first_attempt_scans_);
  if (TakeFinishedAttempt(estimator)) return SearchStep::kLocalized;
  std::optional<Eigen::Isometry3d> guess;
  guess.swap(relocalize_request_);
  const bool attempt_now = due && !Background(map).Busy();
  if (guess || attempt_now) {
    ++scans_initializer_;
    std::shared_future<AttemptClouds> clouds = search_->TakeAttemptClouds(T_search_imu);
    if (guess) {
      // A user's pose (e.g. ROS /initialpose) is judged as given, on the longer cloud.
      const IcpInitializerResult icp =
          icp_initializer_.Initialize(clouds.get().accumulated.Resolve(), map, *guess);
      if (icp.accepted) {
        EndSearch(icp.T_map_imu, estimator, "requested pose accepted: " + icp.message, icp);
        return SearchStep::kLocalized;
      }
      AddEvent(LocalizationEvent::Kind::kSearching, x.t_ns, "requested pose " + icp.message,
               T_search_imu, &icp);
    }
    if (attempt_now) {
      SearchAttempt attempt;
      attempt.T_search_imu = T_search_imu;
      attempt.t_ns = x.t_ns;
      attempt.attempt = search_->attempts();
      attempt.distance_m = search_->distance_m();
      attempt.scans = search_->scans();
      background_->Start(std::move(clouds), LevellingRotation(T_search_imu.linear()), attempt);
      // On the scan thread the attempt has finished: its verdict is applied at once.
      if (TakeFinishedAttempt(estimator)) return SearchStep::kLocalized;
    }
  }
  if (search_->GaveUp()) {
    background_.reset();  // waits for an attempt in flight
    *why = "no pose after searching over " + std::to_string(search_->distance_m()) +
           " m (localization.search.max_distance_m): " + last_attempt_;
    AddEvent(search_is_start_ ? LocalizationEvent::Kind::kInitializationFailed
                              : LocalizationEvent::Kind::kRelocalizationFailed,
             x.t_ns, *why, T_search_imu);
    search_.reset();
    return SearchStep::kGaveUp;
  }
  return SearchStep::kSearching;
}

BackgroundSearch& LocalizationSupervisor::Background(const registration::NeighborSearch& map) {
  if (!background_) {
    background_ = std::make_unique<BackgroundSearch>(*global_, icp_initializer_, sweep_initializer_,
                                                     map, options_.search.background);
  }
  return *background_;
}

void LocalizationSupervisor::StartAttempt(const PointCloud& sweep_imu,
                                          const Eigen::Isometry3d& T_map_imu_guess,
                                          const registration::NeighborSearch& map) {
  ++scans_initializer_;
  SearchAttempt attempt;
  attempt.T_map_imu_guess = T_map_imu_guess;
  // The search frame begins where the vehicle was lost: the guess is the vehicle's pose in it.
  attempt.T_search_imu = T_map_imu_guess;
  attempt.t_ns = search_t_ns_;
  AttemptClouds sweep;
  sweep.accumulated.points = sweep_imu;
  Background(map).Start(Ready(std::move(sweep)), LevellingRotation(T_map_imu_guess.linear()),
                        std::move(attempt));
}

bool LocalizationSupervisor::TakeFinishedAttempt(estimation::Estimator* estimator) {
  if (!background_) return false;
  std::optional<SearchAttempt> done = background_->TakeFinished();
  return done && Conclude(*done, estimator);
}

bool LocalizationSupervisor::ConcludeNearGuess(const SearchAttempt& attempt,
                                               estimation::Estimator* estimator) {
  const IcpInitializerResult& fit = attempt.result.refinement;
  if (!fit.accepted) {
    AddEvent(LocalizationEvent::Kind::kRelocalizationFailed, attempt.t_ns,
             "around the last pose: " + fit.message, attempt.T_search_imu, &fit);
    RestartForSearch(estimator);
    return false;
  }
  const Eigen::Isometry3d T_search_imu = lie::ToIsometry(estimator->state().T_map_imu());
  IcpInitializerResult verdict = fit;
  verdict.T_map_imu = fit.T_map_imu * attempt.T_search_imu.inverse() * T_search_imu;
  EndSearch(verdict.T_map_imu, estimator, fit.message, verdict);
  return true;
}

bool LocalizationSupervisor::Conclude(const SearchAttempt& attempt,
                                      estimation::Estimator* estimator) {
  if (attempt.T_map_imu_guess) return ConcludeNearGuess(attempt, estimator);
  const GlobalLocalizationResult& r = attempt.result;
  std::ostringstream os;
  os << "global localization " << r.message << " (attempt " << attempt.attempt << " after "
     << attempt.distance_m << " m and " << attempt.scans << " scans, " << attempt.points
     << " points, " << r.elapsed_s << " s CPU)";
  last_attempt_ = os.str();
  const Eigen::Isometry3d T_search_imu = lie::ToIsometry(estimator->state().T_map_imu());
  if (r.status != GlobalStatus::kAccepted) {
    AddEvent(LocalizationEvent::Kind::kSearching, attempt.t_ns, last_attempt_,
             attempt.T_search_imu);
    return false;
  }
  // The attempt placed the vehicle in the map at the attempt's scan: the last scans alone,
  // free of the drift the search's odometry gathered farther back, refined that place (kept
  // when accepted; a moving vehicle's few scans can be too sparse on their own). The search
  // frame's odometry since that scan, centimetres over the seconds an attempt takes, carries
  // it to now.
  const IcpInitializerResult& recent = attempt.recent_refinement;
  const Eigen::Isometry3d T_map_imu_then = recent.accepted ? recent.T_map_imu : r.T_map_imu;
  const Eigen::Isometry3d T_map_imu_now =
      T_map_imu_then * attempt.T_search_imu.inverse() * T_search_imu;
  if (attempt.from_recent) os << " on the last " << options_.init_scans << " scans alone";
  IcpInitializerResult verdict = recent.accepted ? recent : r.refinement;
  if (recent.accepted) os << "; last " << options_.init_scans << " scans: " << recent.message;
  verdict.T_map_imu = T_map_imu_now;
  EndSearch(T_map_imu_now, estimator, os.str(), verdict);
  return true;
}

void LocalizationSupervisor::EndSearch(const Eigen::Isometry3d& T_map_imu,
                                       estimation::Estimator* estimator, const std::string& verdict,
                                       const IcpInitializerResult& icp) {
  estimation::NavState x = estimator->state();
  // The search frame placed in the map: every search-frame quantity moves with it.
  const lie::SE3d T_map_search = lie::FromIsometry(T_map_imu) * x.T_map_imu().Inverse();
  x.R_map_imu = T_map_search.so3() * x.R_map_imu;
  x.p_map_imu = T_map_search * x.p_map_imu;
  x.v_map_imu = T_map_search.so3() * x.v_map_imu;
  x.gravity_map = T_map_search.so3() * x.gravity_map;
  estimator->Initialize(x, uncertainty_.LocalizedCovariance());
  // REP-105: the search frame was the odom frame's stand-in, so odom -> imu stays continuous.
  T_map_odom_ = T_map_search * T_map_odom_;
  const bool is_start = search_is_start_;
  background_.reset();  // waits for an attempt in flight: the map is about to change again
  search_.reset();
  if (is_start) {
    started_ = true;
    start_t_ns_ = x.t_ns;
  }
  AddEvent(is_start ? LocalizationEvent::Kind::kInitialized : LocalizationEvent::Kind::kRelocalized,
           x.t_ns, verdict, T_map_imu, &icp);
}

}  // namespace hylo::localization
