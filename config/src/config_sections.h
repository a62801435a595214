#pragma once
// The sections of a run configuration that join an app-level struct to a library one (the
// log's stream beside the estimator's sensor model, ...), so that the field list walks one
// YAML map per section.

#include <string>

#include "hylo/config/run_config.h"

namespace hylo::config {

/// `imu:`: the log's stream and the estimator's sensor model.
struct ImuSection {
  ImuStream& stream;
  estimation::ImuOptions& options;
};
/// `lidar:`: the log's stream and the lidar's clock offset (the pipeline's).
struct LidarSection {
  LidarStream& stream;
  odometry::PipelineLidarOptions& options;
};
/// `localization:`: the start pose given in the file, and the supervisor's settings.
struct LocalizationSection {
  std::string& initial_guess;
  localization::LocalizationOptions& options;
};
/// `output:`: what the pipeline registers for dense maps, and the frame names.
struct OutputSection {
  odometry::PipelineOutputOptions& pipeline;
  OutputFrames& frames;
};

/// Keys that moved or went away: the message an old configuration gets instead of a bare
/// "unknown key" (nullptr for any other key).
const char* MovedKeyHint(const std::string& key_path);

}  // namespace hylo::config
