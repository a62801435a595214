#include "hylo/estimation/backend_base.h"

#include <iterator>

#include "hylo/common/check.h"
#include "hylo/estimation/imu_propagation.h"

namespace hylo::estimation {

BackendBase::BackendBase(const EstimatorOptions& options, const ImuOptions& imu)
    : options_(options),
      imu_options_(imu),
      imu_(imu.enabled, imu.GapNs()),
      robust_(options.robust_registration) {
  std::string why;
  if (!options_.IsValid(&why)) throw InternalError("invalid options: " + why);
  if (!imu_options_.IsValid(&why)) throw InternalError("invalid options: imu." + why);
}

void BackendBase::Restart(const NavState& state) {
  state_ = state;
  constant_velocity_.Reset();
  initialized_ = true;
  imu_.DropBefore(state.t_ns);
}

NavState BackendBase::UpdateStart(const NavState& predicted, const DeskewedScan& scan,
                                  const registration::PlaneMatcher& planes,
                                  const std::function<std::size_t(const NavState&)>& count_matches,
                                  UpdateSummary* summary) {
  NavState start = predicted;
  if (!imu_options_.enabled && options_.no_imu.yaw_search_deg > 0.0) {
    start = SearchYaw(predicted, options_.no_imu, count_matches);
  }
  if (robust_.enabled()) {
    summary->robust = robust_.Align(scan.points_lidar, start.T_map_lidar(), planes);
    start = WithLidarPose(start, summary->robust.T_map_lidar);
  }
  return start;
}

void BackendBase::LearnFromUpdate(const NavState& predicted, const NavState& updated) {
  if (robust_.enabled()) robust_.Observe(predicted.T_map_lidar(), updated.T_map_lidar());
}

StandstillTest BackendBase::TestStandstillBetween(int64_t t0_ns, int64_t t1_ns,
                                                  const Eigen::Vector3d& v_map) const {
  return TestStandstill(imu_.samples(), t0_ns, t1_ns, v_map.norm(), imu_options_,
                        options_.standstill);
}

NavState BackendBase::PredictAt(int64_t t_ns) const {
  const ImuGapModel gap = imu_.GapModel();
  return PredictNominal(state_, imu_.samples(), imu_options_.enabled,
                        constant_velocity_.omega_imu(), t_ns, &gap);
}

std::vector<NavState> BackendBase::PredictAlong(const std::vector<int64_t>& times_ns) const {
  const ImuGapModel gap = imu_.GapModel();
  return PredictNominalAlong(state_, imu_.samples(), imu_options_.enabled,
                             constant_velocity_.omega_imu(), times_ns, &gap);
}

void BackendBase::TakeFinalized(std::vector<NavState>* states) {
  states->insert(states->end(), std::make_move_iterator(finalized_.begin()),
                 std::make_move_iterator(finalized_.end()));
  finalized_.clear();
}

}  // namespace hylo::estimation
