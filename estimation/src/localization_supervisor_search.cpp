// Searching while moving (localization_search.h): the scratch map, the accumulated cloud and
// when to try the global localizer again; and the supervisor's side of it.
#include <optional>
#include <sstream>
#include <utility>

#include "hylo/estimation/localization_search.h"
#include "hylo/estimation/localization_supervisor.h"
#include "hylo/lie/isometry.h"

namespace hylo::estimation {
namespace {

PointCloud Transformed(const Eigen::Isometry3d& T_to_from, const PointCloud& points_from) {
  PointCloud points_to;
  points_to.reserve(points_from.size());
  for (const Eigen::Vector3f& p : points_from) {
    points_to.push_back((T_to_from * p.cast<double>()).cast<float>());
  }
  return points_to;
}

}  // namespace

MovingSearch::MovingSearch(const MovingSearchOptions& options,
                           const mapping::MapManagerOptions& map,
                           const registration::PlaneMatcherOptions& planes, double keep_radius_m,
                           int recent_scans)
    : options_(options),
      keep_radius_m_(keep_radius_m),
      map_(map),
      matcher_(std::make_unique<registration::PlaneMatcher>(map_, planes)),
      cloud_search_(static_cast<float>(options.voxel_m)),
      recent_scans_(recent_scans) {}

void MovingSearch::Begin(const PointCloud& points_imu, const Eigen::Isometry3d& T_search_imu) {
  const PointCloud thinned =
      registration::UniformSample(points_imu, static_cast<float>(options_.voxel_m));
  const PointCloud points_search = Transformed(T_search_imu, thinned);
  map_.AddScan(points_search, T_search_imu.translation().cast<float>());
  cloud_search_.Add(points_search);
  last_position_ = T_search_imu.translation();
  attempt_position_ = last_position_;
}

bool MovingSearch::Add(const PointCloud& sweep_imu, const PointCloud& map_points_search,
                       const Eigen::Isometry3d& T_search_imu, int first_attempt_scans) {
  const PointCloud thinned =
      registration::UniformSample(sweep_imu, static_cast<float>(options_.voxel_m));
  if (!map_points_search.empty()) {
    map_.AddScan(map_points_search, T_search_imu.translation().cast<float>());
  }
  PointCloud thinned_search = Transformed(T_search_imu, thinned);
  cloud_search_.Add(thinned_search);
  recent_search_.push_back(std::move(thinned_search));
  while (static_cast<int>(recent_search_.size()) > recent_scans_) recent_search_.pop_front();
  ++scans_;
  distance_m_ += (T_search_imu.translation() - last_position_).norm();
  last_position_ = T_search_imu.translation();
  if (attempts_ == 0 && first_attempt_scans > 0 && scans_ >= first_attempt_scans) return true;
  return (last_position_ - attempt_position_).norm() >= options_.retry_m;
}

PointCloud MovingSearch::TakeAttemptCloud(const Eigen::Isometry3d& T_search_imu) {
  ++attempts_;
  attempt_position_ = T_search_imu.translation();
  const Eigen::Vector3f center = T_search_imu.translation().cast<float>();
  const float radius_sq = static_cast<float>(keep_radius_m_ * keep_radius_m_);
  PointCloud kept;
  for (const Eigen::Vector3f& p : cloud_search_.points()) {
    if ((p - center).squaredNorm() <= radius_sq) kept.push_back(p);
  }
  if (kept.size() < cloud_search_.points().size()) {
    registration::UniformSampler cropped(static_cast<float>(options_.voxel_m));
    cropped.Add(kept);
    cloud_search_ = std::move(cropped);
  }
  return Transformed(T_search_imu.inverse(), kept);
}

PointCloud MovingSearch::RecentInImu(const Eigen::Isometry3d& T_search_imu) const {
  const Eigen::Isometry3d T_imu_search = T_search_imu.inverse();
  PointCloud recent_imu;
  for (const PointCloud& sweep : recent_search_) {
    const PointCloud sweep_imu = Transformed(T_imu_search, sweep);
    recent_imu.insert(recent_imu.end(), sweep_imu.begin(), sweep_imu.end());
  }
  return recent_imu;
}

bool MovingSearch::GaveUp() const {
  return options_.max_distance_m > 0.0 && distance_m_ > options_.max_distance_m;
}

bool LocalizationSupervisor::RequestGlobalLocalization(std::string* why) {
  if (!options_.global_enabled || global_map_ == nullptr) {
    *why = global_map_ == nullptr ? "no global map: " + global_map_unavailable_
                                  : "global localization is disabled "
                                    "(localization.global_enabled)";
    return false;
  }
  if (!started_ && !searching()) {
    guess_.reset();  // the start searches the whole map
    return true;
  }
  if (!searching()) global_request_ = true;
  return true;
}

void LocalizationSupervisor::BeginSearch(const NavState& x, const PointCloud& points_imu,
                                         bool is_start, const std::string& reason) {
  search_ = std::make_unique<MovingSearch>(options_.search, search_map_, search_planes_,
                                           options_.global.max_range_m, options_.init_scans);
  search_->Begin(points_imu, lie::ToIsometry(x.T_map_imu()));
  search_is_start_ = is_start;
  lost_ = false;
  bad_scans_in_row_ = 0;
  AddEvent(LocalizationEvent::Kind::kSearching, x.t_ns,
           reason + "; searching while the vehicle moves (no pose until one is accepted)",
           lie::ToIsometry(x.T_map_imu()));
}

LocalizationSupervisor::SearchStep LocalizationSupervisor::Search(
    const PointCloud& sweep_imu, const PointCloud& map_points_search,
    const registration::NeighborSearch& map, Estimator* estimator, std::string* why) {
  const NavState x = estimator->state();
  const Eigen::Isometry3d T_search_imu = lie::ToIsometry(x.T_map_imu());
  // Begun on request, a standing vehicle tries once it has as many scans as a start.
  const int first_attempt_scans = search_is_start_ ? 0 : options_.init_scans;
  const bool due = search_->Add(sweep_imu, map_points_search, T_search_imu, first_attempt_scans);
  std::optional<Eigen::Isometry3d> guess;
  guess.swap(relocalize_request_);
  if (!due && !guess) return SearchStep::kSearching;
  ++scans_initializer_;
  const PointCloud cloud_imu = search_->TakeAttemptCloud(T_search_imu);
  if (guess) {
    // A user's pose (e.g. ROS /initialpose) is judged as given, on the longer cloud.
    const registration::IcpInitializerResult icp =
        icp_initializer_.Initialize(cloud_imu, map, *guess);
    if (icp.accepted) {
      EndSearch(icp.T_map_imu, estimator, "requested pose accepted: " + icp.message, icp);
      return SearchStep::kLocalized;
    }
    AddEvent(LocalizationEvent::Kind::kSearching, x.t_ns, "requested pose " + icp.message,
             T_search_imu, &icp);
    if (!due) return SearchStep::kSearching;
  }
  const registration::GlobalLocalizationResult r = global_localizer_.Localize(
      cloud_imu, registration::LevellingRotation(T_search_imu.linear()), *global_map_, map);
  std::ostringstream os;
  os << "global localization " << r.message << " (attempt " << search_->attempts() << " after "
     << search_->distance_m() << " m and " << search_->scans() << " scans, " << cloud_imu.size()
     << " points, " << r.elapsed_s << " s CPU)";
  if (r.status == registration::GlobalStatus::kAccepted) {
    // The accumulated cloud found the place; the last scans alone, free of the drift of the
    // search's odometry farther back, place the vehicle now (the whole cloud is kept when
    // they fail: a moving vehicle's few scans can be too sparse to pass on their own).
    const registration::IcpInitializerResult recent =
        icp_initializer_.Initialize(search_->RecentInImu(T_search_imu), map, r.T_map_imu);
    if (recent.accepted) {
      os << "; last " << options_.init_scans << " scans: " << recent.message;
      EndSearch(recent.T_map_imu, estimator, os.str(), recent);
    } else {
      EndSearch(r.T_map_imu, estimator, os.str(), r.refinement);
    }
    return SearchStep::kLocalized;
  }
  if (search_->GaveUp()) {
    *why = "no pose after searching over " + std::to_string(search_->distance_m()) +
           " m (localization.search.max_distance_m): " + os.str();
    AddEvent(search_is_start_ ? LocalizationEvent::Kind::kInitializationFailed
                              : LocalizationEvent::Kind::kRelocalizationFailed,
             x.t_ns, *why, T_search_imu);
    search_.reset();
    return SearchStep::kGaveUp;
  }
  AddEvent(LocalizationEvent::Kind::kSearching, x.t_ns, os.str(), T_search_imu);
  return SearchStep::kSearching;
}

void LocalizationSupervisor::EndSearch(const Eigen::Isometry3d& T_map_imu, Estimator* estimator,
                                       const std::string& verdict,
                                       const registration::IcpInitializerResult& icp) {
  NavState x = estimator->state();
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
  search_.reset();
  if (is_start) {
    started_ = true;
    start_t_ns_ = x.t_ns;
  }
  AddEvent(is_start ? LocalizationEvent::Kind::kInitialized : LocalizationEvent::Kind::kRelocalized,
           x.t_ns, verdict, T_map_imu, &icp);
}

}  // namespace hylo::estimation
