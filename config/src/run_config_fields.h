#pragma once
// The single list of configuration fields. Every reader and writer walks these functions: the
// YAML reader (so a field added here is parsed and known to the unknown-key check), the YAML
// and JSON writers, and the reference doc (docs/configuration.md, from the descriptions here).
// Visitor interface:
//   v(key, field, description)                            a value
//   v.Section(key, struct, description)                   a nested map
//   v.OptionalSection(key, struct, enabled, description)  a map that may be the scalar `none`
// Each YAML section maps onto one library options struct (plus, for a few sections, an
// app-level struct beside it, config_sections.h): the key names are the structs' field names.
// A description says what the field does, its unit and its constraint, in a line or two; the
// library headers' ///< comments say the same for a programmer, with the reasons.

#include "config_sections.h"
#include "fields_estimation.h"
#include "fields_ground.h"
#include "fields_inspection.h"
#include "fields_localization.h"
#include "fields_sensors.h"

namespace hylo::config {

template <class V>
void VisitFields(V& v, RunConfig& run) {
  odometry::OdometryPipelineOptions& p = run.pipeline;
  LidarSection lidar{run.lidar, p.lidar};
  ImuSection imu{run.imu, p.imu};
  LocalizationSection localization{run.initial_guess, p.localization};
  OutputSection output{p.output, run.output};
  v("backend", p.estimator.backend,
    "the estimator: the iterated error-state Kalman filter, or the sliding-window smoother "
    "(IMU preintegration and point-to-plane factors over the last scans, solved by Ceres)");
  v("threads", p.threads,
    "threads for each scan's per-point work (preprocessing, plane association, both "
    "back-ends' residuals): 0 = every core, 1 = one thread; the poses are the same for any "
    "value, >= 0");
  v.Section("lidar", lidar, "the lidar stream in the log, and its clock");
  v.OptionalSection("imu", imu, p.imu.enabled,
                    "the IMU stream in the log and its sensor model; `imu: none` runs "
                    "lidar-only with a constant-velocity model");
  v.Section("T_imu_lidar", run.T_imu_lidar,
            "the lidar's mounting: maps lidar points into the IMU (body) frame, "
            "R = Rz(yaw) Ry(pitch) Rx(roll)");
  v.Section("preprocess", p.preprocess, "clean-up and sampling of each scan");
  v.Section("init", p.init, "the static start: gravity and gyro bias from the IMU at rest");
  v.Section("initial_uncertainty", p.initial_uncertainty,
            "the estimator's starting standard deviations, in SLAM and after an ICP start");
  v.Section("lidar_update", p.estimator.lidar_update,
            "the point-to-plane measurement, both back-ends");
  v.Section("no_imu", p.estimator.no_imu,
            "the motion model and aids used without an IMU, both back-ends");
  v.Section("robust_registration", p.estimator.robust_registration,
            "a robust, wide-basin alignment before each lidar update, both back-ends: for "
            "lidar-only runs (with an IMU the prediction is good enough)");
  v.Section("standstill", p.estimator.standstill,
            "zero-velocity updates while the IMU shows the vehicle at rest, both back-ends");
  v.Section("ieskf", p.estimator.ieskf, "the iterated error-state Kalman filter (backend: ieskf)");
  v.Section("sliding_window", p.estimator.sliding_window,
            "the sliding-window smoother (backend: sliding_window)");
  v.Section("planes", p.planes, "plane matching of scan points against the map, both back-ends");
  v.Section("map", p.map, "the map the estimator registers against while it runs");
  v.Section("prior_map", run.prior_map, "how a prior map is thinned and, when tiled, streamed");
  v.Section("localization", localization,
            "localization in a prior map: the start, health, relocalization and hybrid mapping");
  v.Section("output", output,
            "what a run writes beyond the poses, and the frame names of its outputs (REP-105)");
  v.Section("ground", run.ground,
            "ground extraction of a finished map (the mapping chain of hylo demo); the defaults "
            "suit a ground robot's map, and both back-ends' options are checked whichever runs");
  v.Section("inspection", run.inspection,
            "inspection planning (hylo inspect): where to stand to see each target, and the "
            "route there");
}

}  // namespace hylo::config
