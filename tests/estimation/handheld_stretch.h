#pragma once
// The real hand-held stretches of the data README (BALM walk, 2 Hz, no IMU) run through the
// odometry pipeline, with the figures the robustness test and the hand-held benchmark
// report: ATE after SE(3) alignment, the worst one-scan step error and CPU time per scan.

#include <string>
#include <vector>

#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/evaluation/trajectory_metrics.h"

namespace hylo::testing {

/// Folders (relative to the data directory) of the three stretches: scans 20-39, 40-59 and
/// 100-119 of the walk.
const std::vector<std::string>& HandheldStretches();
/// The stretches' folders under `data_dir`.
std::vector<std::string> HandheldStretchDirs(const std::string& data_dir);

struct StretchRun {
  std::size_t scans = 0;            ///< processed scans
  evaluation::AteResult ate;        ///< SE(3)-aligned, against poses.csv
  double worst_step_m = 0.0;        ///< largest one-scan relative translation error, m
  double worst_step_deg = 0.0;      ///< largest one-scan relative rotation error, deg
  std::vector<double> cpu_ms;       ///< per processed scan, thread CPU time, ms
  std::size_t retried_scans = 0;    ///< scans whose robust alignment tried yaw hypotheses
  std::size_t unchecked_scans = 0;  ///< scans whose best alignment still failed the check
  std::size_t not_applied = 0;      ///< scans whose update was not applied
  std::vector<odometry::ScanResult> results;
};

/// Runs the scan folder `dir` through a pipeline with `options`, keeping every `stride`-th
/// scan (2: the same walk sampled at 1 Hz, twice the motion between scans) and at most
/// `max_scans` of them (0 = all). Throws std::runtime_error when the folder cannot be read.
StretchRun RunStretch(const std::string& dir, const odometry::OdometryPipelineOptions& options,
                      int stride = 1, std::size_t max_scans = 0);

/// The q-quantile (0..1) of `values`, nearest rank; 0 when empty.
double Quantile(std::vector<double> values, double q);

}  // namespace hylo::testing
