// Uses one piece of each installed library; exits 0 when they link and behave.
#include <hylo/common/local_origin.h>
#include <hylo/common/sensor_data.h>
#include <hylo/config/run_config.h>
#include <hylo/io/json.h>
#include <hylo/registration/voxel_filter.h>

int main() {
  const hylo::PointCloud cloud = {{0.1f, 0.1f, 0.1f}, {0.2f, 0.2f, 0.2f}};
  const bool sampled = hylo::registration::UniformSample(cloud, 1.0f).size() == 1;
  const bool origin = hylo::ChooseOrigin({{412345.6, 4.5e6, 12.0}}).x() == 412300.0;
  const bool config = !hylo::config::ParseRunConfig("imu: none\n", "consumer").pipeline.imu.enabled;
  hylo::io::Json json;
  json["ok"] = sampled && origin && config;
  return json.dump() == "{\"ok\":true}" ? 0 : 1;
}
