// Recovery cases: where a drive's data are cut (or its log begins), and the sink that cuts them.
#include "localization/recovery_cases.h"

#include <algorithm>
#include <cmath>

#include "hylo/common/check.h"
#include "hylo/common/time.h"
#include "hylo/sim/random.h"

namespace hylo::testing {
namespace {

constexpr int64_t kStepNs = 50'000'000;  // distance sampling, ns
constexpr int kMaxDraws = 64;            // tries to place one case before leaving it out

bool InYard(const Eigen::Vector3d& p, const Eigen::Vector2d& yard_size_m) {
  return p.x() >= 0.0 && p.y() >= 0.0 && p.x() <= yard_size_m.x() && p.y() <= yard_size_m.y();
}

}  // namespace

std::string ToString(RecoveryKind kind) {
  switch (kind) {
    case RecoveryKind::kGapAll:
      return "gap_all";
    case RecoveryKind::kGapLidar:
      return "gap_lidar";
    case RecoveryKind::kMovingStart:
      return "moving_start";
  }
  return "?";
}

bool ParseRecoveryKind(const std::string& name, RecoveryKind* kind) {
  for (const RecoveryKind k : AllRecoveryKinds()) {
    if (ToString(k) == name) {
      *kind = k;
      return true;
    }
  }
  return false;
}

std::vector<RecoveryKind> AllRecoveryKinds() {
  return {RecoveryKind::kGapAll, RecoveryKind::kGapLidar, RecoveryKind::kMovingStart};
}

DriveTruth::DriveTruth(const sim::ScenarioSimulator& drive)
    : drive_(drive),
      start_ns_(drive.start_ns()),
      end_ns_(drive.start_ns() + drive.duration_ns()),
      motion_start_ns_(end_ns_) {
  const sim::Trajectory& vehicle = drive.motion().vehicle();
  Eigen::Vector3d previous = vehicle.PoseAt(0).translation();
  double distance_m = 0.0;
  for (int64_t t = 0; t <= drive.duration_ns(); t += kStepNs) {
    const Eigen::Vector3d p = vehicle.PoseAt(t).translation();
    distance_m += (p - previous).norm();
    previous = p;
    distance_m_.push_back(distance_m);
    // Suspension jitter moves a standing vehicle by millimetres; driving is centimetres a step.
    if (motion_start_ns_ == end_ns_ && distance_m > 0.05) motion_start_ns_ = start_ns_ + t;
  }
}

Eigen::Isometry3d DriveTruth::PoseAt(int64_t t_ns) const {
  return drive_.motion().PoseAt(std::clamp<int64_t>(t_ns - start_ns_, 0, end_ns_ - start_ns_));
}

double DriveTruth::DistanceAt(int64_t t_ns) const {
  const double k = static_cast<double>(t_ns - start_ns_) / kStepNs;
  if (k <= 0.0) return 0.0;
  const std::size_t i = static_cast<std::size_t>(k);
  if (i + 1 >= distance_m_.size()) return distance_m_.back();
  return distance_m_[i] + (k - i) * (distance_m_[i + 1] - distance_m_[i]);
}

int64_t DriveTruth::TimeAtDistance(double distance_m) const {
  const auto it = std::lower_bound(distance_m_.begin(), distance_m_.end(), distance_m);
  if (it == distance_m_.end()) return end_ns_;
  return std::min(end_ns_, start_ns_ + kStepNs * static_cast<int64_t>(it - distance_m_.begin()));
}

double DriveTruth::SpeedAt(int64_t t_ns) const {
  constexpr int64_t kHalfNs = 100'000'000;
  const int64_t from = std::max(start_ns_, t_ns - kHalfNs), to = std::min(end_ns_, t_ns + kHalfNs);
  return to > from ? (DistanceAt(to) - DistanceAt(from)) / NanosToSeconds(to - from) : 0.0;
}

bool PlaceRecoveryCase(RecoveryKind kind, double after_motion_s, double distance_m,
                       const DriveTruth& truth, const RecoveryDrawOptions& options,
                       RecoveryCase* out) {
  RecoveryCase c;
  c.kind = kind;
  c.cut_t_ns = truth.motion_start_ns() + SecondsToNanos(after_motion_s);
  if (kind == RecoveryKind::kMovingStart) {
    c.return_t_ns = c.cut_t_ns;
  } else {
    c.drawn_distance_m = c.distance_m = distance_m;
    c.return_t_ns = truth.TimeAtDistance(truth.DistanceAt(c.cut_t_ns) + distance_m);
  }
  c.end_t_ns = c.return_t_ns + SecondsToNanos(options.window_s);
  if (c.end_t_ns > truth.end_ns()) return false;
  c.speed_mps = truth.SpeedAt(c.return_t_ns);
  *out = c;
  return true;
}

namespace {

// A gap: the drawn travel, shortened to what the drive holds between the earliest cut and the
// latest return; the cut placed uniformly along the travel that leaves room for it.
bool DrawGap(RecoveryKind kind, const DriveTruth& truth, const RecoveryDrawOptions& options,
             sim::Rng* rng, RecoveryCase* out) {
  const int64_t earliest_ns = truth.motion_start_ns() + SecondsToNanos(options.tracking_before_s);
  const double first_m = truth.DistanceAt(earliest_ns);
  const double last_m = truth.DistanceAt(truth.end_ns() - SecondsToNanos(options.window_s));
  const double drawn_m = rng->Uniform(options.min_gap_m, options.max_gap_m);
  const double gap_m = std::min(drawn_m, last_m - first_m - 0.5);
  if (gap_m < options.min_gap_m) return false;
  const int64_t cut_ns = truth.TimeAtDistance(rng->Uniform(first_m, last_m - gap_m));
  if (!PlaceRecoveryCase(kind,
                         NanosToSeconds(std::max(cut_ns, earliest_ns) - truth.motion_start_ns()),
                         gap_m, truth, options, out)) {
    return false;
  }
  out->drawn_distance_m = drawn_m;
  return true;
}

bool DrawMovingStart(const DriveTruth& truth, const RecoveryDrawOptions& options, sim::Rng* rng,
                     RecoveryCase* out) {
  const double latest_s =
      NanosToSeconds(truth.end_ns() - truth.motion_start_ns()) - options.window_s;
  if (latest_s < 1.0) return false;
  if (!PlaceRecoveryCase(RecoveryKind::kMovingStart, rng->Uniform(1.0, latest_s), 0.0, truth,
                         options, out)) {
    return false;
  }
  return out->speed_mps >= options.min_speed_mps && out->speed_mps <= options.max_speed_mps;
}

}  // namespace

std::vector<RecoveryCase> DrawRecoveryCases(uint64_t scenario, const DriveTruth& truth,
                                            const Eigen::Vector2d& yard_size_m,
                                            const RecoveryDrawOptions& options) {
  const std::vector<RecoveryKind> kinds = AllRecoveryKinds();
  std::vector<RecoveryCase> cases;
  for (int index = 0; index < options.cases; ++index) {
    const RecoveryKind kind = kinds[(scenario + static_cast<uint64_t>(index)) % kinds.size()];
    sim::Rng rng = sim::Rng::Derive(scenario, 0x7ec0 + options.seed, static_cast<uint64_t>(index));
    for (int draw = 0; draw < kMaxDraws; ++draw) {
      RecoveryCase c;
      const bool placed = kind == RecoveryKind::kMovingStart
                              ? DrawMovingStart(truth, options, &rng, &c)
                              : DrawGap(kind, truth, options, &rng, &c);
      if (!placed || !InYard(truth.PoseAt(c.return_t_ns).translation(), yard_size_m)) continue;
      c.scenario = scenario;
      c.index = index;
      cases.push_back(c);
      break;
    }
  }
  return cases;
}

RecoveryRun::RecoveryRun(const RecoveryCase& recovery_case,
                         const odometry::OdometryPipelineOptions& options,
                         const mapping::PriorMap& prior,
                         const std::optional<Eigen::Isometry3d>& T_world_imu_guess,
                         int64_t lidar_time_offset_ns)
    : case_(recovery_case),
      session_(options, run::SessionKeeps{true, false, true}),
      origin_world_(prior.origin_world),
      lidar_time_offset_ns_(lidar_time_offset_ns) {
  // The map is thinned once for every case; each session takes it in its local frame.
  session_.pipeline().SetPriorMap(prior.points_local);
  std::optional<Eigen::Isometry3d> guess_local;
  if (T_world_imu_guess) guess_local = mapping::PoseToLocal(*T_world_imu_guess, origin_world_);
  session_.pipeline().SetInitialGuess(guess_local);
}

bool RecoveryRun::Kept(int64_t from_ns, int64_t to_ns, bool imu) const {
  if (to_ns >= case_.end_t_ns) return false;
  if (case_.kind == RecoveryKind::kMovingStart) return from_ns >= case_.cut_t_ns;
  if (imu && case_.kind == RecoveryKind::kGapLidar) return true;
  return to_ns < case_.cut_t_ns || from_ns >= case_.return_t_ns;
}

void RecoveryRun::OnImu(const ImuSample& s) {
  if (Kept(s.t_ns, s.t_ns, /*imu=*/true)) session_.AddImu(s);
}

void RecoveryRun::OnScan(const LidarScan& s) {
  if (Kept(s.t_ns - lidar_time_offset_ns_, s.end_t_ns - lidar_time_offset_ns_, /*imu=*/false)) {
    session_.AddScan(s);
  }
}

}  // namespace hylo::testing
