// Drawing a scenario from its number; easing one factor; the sensor sheet.
#include "hylo/sim/scenario.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "hylo/sim/random.h"

namespace hylo::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Geometric interpolation between a tactical (g = 0) and a consumer (g = 1) figure, with a
// spread of a factor 0.7-1.4 so two scenarios of one grade differ.
double GradeValue(double tactical, double consumer, double g, Rng* rng) {
  return tactical * std::pow(consumer / tactical, g) * rng->Uniform(0.7, 1.4);
}

ImuGrade DrawImu(Rng* rng) {
  ImuGrade imu;
  const double g = rng->Uniform();
  imu.grade = g;
  ImuOptions& b = imu.base;
  const double rates[3] = {100.0, 200.0, 400.0};
  b.rate_hz = rates[std::min(2, static_cast<int>(rng->Uniform(0.0, 3.0)))];
  b.gravity_mps2 = rng->Uniform(9.78, 9.83);
  // Tactical: FOG/tactical MEMS (0.007 deg/sqrt(h), 50 ug/sqrt(Hz)); consumer: phone-class
  // MEMS (0.017 deg/s/sqrt(Hz), 300 ug/sqrt(Hz)), turn-on biases of 1 deg/s and 10 mg.
  b.gyro_noise_density = GradeValue(2e-6, 3e-4, g, rng);
  b.accel_noise_density = GradeValue(5e-4, 3e-3, g, rng);
  b.gyro_bias_random_walk = GradeValue(2e-7, 6e-5, g, rng);
  b.accel_bias_random_walk = GradeValue(5e-6, 8e-4, g, rng);
  b.gyro_bias_initial_sigma = GradeValue(5e-5, 0.017, g, rng);
  b.accel_bias_initial_sigma = GradeValue(0.005, 0.1, g, rng);
  imu.gyro_bias_instability_radps = GradeValue(5e-6, 2e-4, g, rng);
  imu.accel_bias_instability_mps2 = GradeValue(5e-5, 1e-3, g, rng);
  imu.bias_correlation_s = rng->Uniform(50.0, 300.0);
  imu.accel_scale_sigma = GradeValue(1e-4, 1e-2, g, rng);
  imu.gyro_scale_sigma = GradeValue(1e-4, 1e-2, g, rng);
  imu.misalignment_sigma_rad = GradeValue(1e-4, 5e-3, g, rng);
  return imu;
}

Eigen::Matrix3d UniformRotation(Rng* rng) {
  Eigen::Quaterniond q(rng->Gaussian(), rng->Gaussian(), rng->Gaussian(), rng->Gaussian());
  return q.normalized().toRotationMatrix();
}

// The lidar on the vehicle: a spinning head upright within 10 deg at any heading, a
// forward-looking rosette pitched down by up to 15 deg; 0.05-0.5 m from the IMU, above it.
Eigen::Isometry3d DrawLidarOnVehicle(SensorKind kind, Rng* rng) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (kind == SensorKind::kLivoxRosette) {
    T.linear() =
        RotationFromYawPitchRoll(rng->Uniform(-20.0, 20.0) * kDeg, rng->Uniform(0.0, 15.0) * kDeg,
                                 rng->Uniform(-5.0, 5.0) * kDeg);
  } else {
    T.linear() = RotationFromYawPitchRoll(rng->Uniform(-180.0, 180.0) * kDeg,
                                          rng->Uniform(-10.0, 10.0) * kDeg,
                                          rng->Uniform(-10.0, 10.0) * kDeg);
  }
  Eigen::Vector3d lever(rng->Uniform(-0.35, 0.35), rng->Uniform(-0.35, 0.35),
                        rng->Uniform(0.0, 0.45));
  const double length = rng->Uniform(0.05, 0.5);
  if (lever.norm() > 1e-9) lever *= length / lever.norm();
  T.translation() = lever;
  return T;
}

Vibration DrawVibration(double imu_rate_hz, Rng* rng) {
  Vibration v;
  // Below 0.45 of the IMU rate: an IMU's anti-alias filter would remove the rest.
  const double f_max = std::min(45.0, 0.45 * imu_rate_hz);
  for (int k = 0; k < 2; ++k) {
    const double f = rng->Uniform(8.0, f_max);
    const double w2 = std::pow(2.0 * M_PI * f, 2);
    Vibration::Tone t, r;
    t.frequency_hz = r.frequency_hz = f;
    for (int i = 0; i < 3; ++i) {
      t.amplitude[i] = rng->Uniform(0.05, 1.0) / w2;  // 0.05-1 m/s^2 of acceleration
      r.amplitude[i] = rng->Uniform(0.002, 0.03) / (2.0 * M_PI * f);  // 0.002-0.03 rad/s
      t.phase_rad[i] = rng->Uniform(0.0, 2.0 * M_PI);
      r.phase_rad[i] = rng->Uniform(0.0, 2.0 * M_PI);
    }
    v.translation.push_back(t);
    v.rotation.push_back(r);
  }
  return v;
}

SiteRecipe DrawSite(Rng* rng) {
  SiteRecipe s;
  s.yard_size_m = {rng->Uniform(50.0, 130.0), rng->Uniform(40.0, 90.0)};
  s.bay_m = {rng->Uniform(14.0, 24.0), rng->Uniform(14.0, 24.0)};
  s.structure_density = rng->Uniform(0.15, 0.9);
  s.clutter_per_100m2 = rng->Uniform(0.0, 0.6);
  s.hills = static_cast<int>(rng->Uniform(0.0, 5.0));
  s.trenches = static_cast<int>(rng->Uniform(0.0, 4.0));
  s.bumps = static_cast<int>(rng->Uniform(0.0, 7.0));
  s.undulation_m = rng->Uniform(0.05, 0.3);
  s.undulation_wavelength_m = rng->Uniform(15.0, 40.0);
  s.gravel_sigma_m = rng->Uniform(0.005, 0.03);
  s.featureless_m = rng->Uniform() < 0.5 ? rng->Uniform(25.0, 70.0) : 0.0;
  s.start_slope_deg = rng->Uniform(0.0, 20.0);
  return s;
}

// Rounds to `step` (e.g. 0.001 for a millimetre).
double RoundTo(double value, double step) { return std::round(value / step) * step; }

// Two significant digits, as datasheets state noise figures.
double TwoDigits(double value) {
  if (value == 0.0) return 0.0;
  const double scale = std::pow(10.0, std::floor(std::log10(std::abs(value))) - 1.0);
  return std::round(value / scale) * scale;
}

}  // namespace

std::string ImuGrade::Label() const {
  return grade < 1.0 / 3.0 ? "tactical" : grade < 2.0 / 3.0 ? "industrial" : "consumer";
}

Scenario DrawScenario(uint64_t number) {
  Scenario s;
  s.number = number;
  Rng rng = Rng::Derive(number, 0x5ce7a210);
  const std::vector<SensorKind> kinds = AllSensorKinds();
  s.lidar = SensorSpec::For(kinds[(number / 2) % kinds.size()]);
  s.lidar.range_noise_m *= rng.Uniform(0.8, 1.5);
  s.site = DrawSite(&rng);
  s.imu = DrawImu(&rng);
  s.R_vehicle_imu = UniformRotation(&rng);
  const Eigen::Isometry3d T_vehicle_lidar = DrawLidarOnVehicle(s.lidar.kind, &rng);
  Eigen::Isometry3d T_vehicle_imu = Eigen::Isometry3d::Identity();
  T_vehicle_imu.linear() = s.R_vehicle_imu;
  s.T_imu_lidar = T_vehicle_imu.inverse() * T_vehicle_lidar;
  s.lidar_time_offset_ns = std::llround(rng.Uniform(-15e6, 15e6));
  TrajectoryOptions& t = s.trajectory;
  t.cruise_speed_mps = rng.Uniform(0.5, 3.0);
  t.max_accel_mps2 = rng.Uniform(0.3, 1.0);
  t.max_lateral_accel_mps2 = rng.Uniform(0.3, 1.0);
  t.min_turn_speed_mps = std::min(0.5, t.cruise_speed_mps);
  t.jitter_z_m = rng.Uniform(0.002, 0.008);
  t.jitter_tilt_rad = rng.Uniform(0.002, 0.008);
  // 70-85 s of mapping and 35-45 s of localization at cruise speed (turns take longer).
  s.site.route_a_m = t.cruise_speed_mps * rng.Uniform(70.0, 85.0);
  s.site.route_b_m = t.cruise_speed_mps * rng.Uniform(35.0, 45.0);
  // The spur (out, a turning loop, back) takes at most 60 % of the mapping drive; slow
  // drives too short for a 15 m spur have none.
  const double longest_spur_m = 0.3 * s.site.route_a_m - 20.0;
  s.site.featureless_m = std::min(s.site.featureless_m, longest_spur_m);
  if (s.site.featureless_m < 15.0) s.site.featureless_m = 0.0;
  s.vibration = DrawVibration(s.imu.base.rate_hz, &rng);
  return s;
}

std::string Scenario::Summary() const {
  char line[256];
  std::snprintf(
      line, sizeof(line),
      "%s, %s IMU (%.0f Hz), %.1f m/s, start slope %.0f deg, %s, clock offset %+.1f ms",
      ToString(lidar.kind).c_str(), imu.Label().c_str(), imu.base.rate_hz,
      trajectory.cruise_speed_mps, site.start_slope_deg,
      site.featureless_m > 0.0
          ? ("empty spur " + std::to_string(static_cast<int>(site.featureless_m)) + " m").c_str()
          : "no empty spur",
      1e-6 * static_cast<double>(lidar_time_offset_ns));
  return line;
}

std::vector<ScenarioFactor> AllScenarioFactors() {
  return {ScenarioFactor::kImuGrade,    ScenarioFactor::kSpeed,       ScenarioFactor::kVibration,
          ScenarioFactor::kMounting,    ScenarioFactor::kClockOffset, ScenarioFactor::kStartSlope,
          ScenarioFactor::kFeatureless, ScenarioFactor::kSensor};
}

std::string ToString(ScenarioFactor factor) {
  switch (factor) {
    case ScenarioFactor::kImuGrade:
      return "imu_grade";
    case ScenarioFactor::kSpeed:
      return "speed";
    case ScenarioFactor::kVibration:
      return "vibration";
    case ScenarioFactor::kMounting:
      return "mounting";
    case ScenarioFactor::kClockOffset:
      return "clock_offset";
    case ScenarioFactor::kStartSlope:
      return "start_slope";
    case ScenarioFactor::kFeatureless:
      return "featureless_spur";
    case ScenarioFactor::kSensor:
      return "sensor";
  }
  return "?";
}

Scenario Eased(const Scenario& scenario, ScenarioFactor factor) {
  Scenario s = scenario;
  switch (factor) {
    case ScenarioFactor::kImuGrade: {
      const ImuOptions rate_and_gravity = s.imu.base;
      s.imu = ImuGrade();
      s.imu.grade = 0.0;
      s.imu.base.rate_hz = rate_and_gravity.rate_hz;
      s.imu.base.gravity_mps2 = rate_and_gravity.gravity_mps2;
      s.imu.base.gyro_noise_density = 2e-6;
      s.imu.base.accel_noise_density = 5e-4;
      s.imu.base.gyro_bias_random_walk = 2e-7;
      s.imu.base.accel_bias_random_walk = 5e-6;
      s.imu.base.gyro_bias_initial_sigma = 5e-5;
      s.imu.base.accel_bias_initial_sigma = 0.005;
      break;
    }
    case ScenarioFactor::kSpeed:
      s.trajectory.cruise_speed_mps = 1.0;
      s.trajectory.max_accel_mps2 = 0.3;
      s.trajectory.max_lateral_accel_mps2 = 0.25;
      s.trajectory.min_turn_speed_mps = 0.5;
      break;
    case ScenarioFactor::kVibration:
      s.vibration = Vibration();
      s.trajectory.jitter_z_m = s.trajectory.jitter_tilt_rad = 0.0;
      break;
    case ScenarioFactor::kMounting: {
      s.R_vehicle_imu.setIdentity();
      s.T_imu_lidar.setIdentity();
      if (s.lidar.kind == SensorKind::kLivoxRosette) {
        s.T_imu_lidar.linear() = RotationFromYawPitchRoll(0.0, 5.0 * kDeg, 0.0);
      }
      s.T_imu_lidar.translation() = Eigen::Vector3d(0.0, 0.0, 0.1);
      break;
    }
    case ScenarioFactor::kClockOffset:
      s.lidar_time_offset_ns = 0;
      break;
    case ScenarioFactor::kStartSlope:
      s.site.start_slope_deg = 0.0;
      break;
    case ScenarioFactor::kFeatureless:
      s.site.featureless_m = 0.0;
      break;
    case ScenarioFactor::kSensor: {
      const double noise_scale =
          s.lidar.range_noise_m / SensorSpec::For(s.lidar.kind).range_noise_m;
      s.lidar = SensorSpec::For(SensorKind::kVlp16);
      s.lidar.range_noise_m *= noise_scale;
      break;
    }
  }
  return s;
}

SensorSheet SheetOf(const Scenario& scenario) {
  SensorSheet sheet;
  sheet.scenario = scenario.number;
  sheet.sensor = ToString(scenario.lidar.kind);
  sheet.preset = scenario.lidar.preset;
  const Eigen::Vector3d t = scenario.T_imu_lidar.translation();
  Eigen::Vector3d ypr = scenario.T_imu_lidar.linear().eulerAngles(2, 1, 0) / kDeg;
  if (std::abs(ypr[1]) > 90.0) {  // the other ZYX solution, with pitch within +-90 deg
    ypr = Eigen::Vector3d(ypr[0] + 180.0, (ypr[1] > 0.0 ? 180.0 : -180.0) - ypr[1], ypr[2] + 180.0);
  }
  for (int i = 0; i < 3; ++i) ypr[i] = std::remainder(ypr[i], 360.0);
  for (int i = 0; i < 3; ++i) {
    sheet.translation_m[i] = RoundTo(t[i], 0.001);
    sheet.rotation_rpy_deg[i] = RoundTo(ypr[2 - i], 0.1);
  }
  const ImuOptions& imu = scenario.imu.base;
  sheet.imu_rate_hz = imu.rate_hz;
  sheet.gyro_noise_density = TwoDigits(imu.gyro_noise_density);
  sheet.accel_noise_density = TwoDigits(imu.accel_noise_density);
  sheet.gyro_bias_random_walk = TwoDigits(imu.gyro_bias_random_walk);
  sheet.accel_bias_random_walk = TwoDigits(imu.accel_bias_random_walk);
  sheet.lidar_time_offset_s =
      RoundTo(1e-9 * static_cast<double>(scenario.lidar_time_offset_ns), 1e-3);
  return sheet;
}

std::string SensorSheet::ToYaml() const {
  std::ostringstream os;
  os.precision(9);
  os << "# Sensor sheet of simulator scenario " << scenario << " (hylo simulate --scenario "
     << scenario << ").\n"
     << "# Configure a run from config/" << preset << ".yaml with the values below (that is\n"
     << "# what config.yaml next to the bags is). Not known to the user, hence not here: local\n"
     << "# gravity, turn-on biases, bias instability, scale and axis errors, vibration.\n"
     << "sensor: " << sensor << "\n"
     << "preset: " << preset << "\n"
     << "T_imu_lidar:                       # from the mounting drawing (1 mm, 0.1 deg)\n"
     << "  translation_m: [" << translation_m.x() << ", " << translation_m.y() << ", "
     << translation_m.z() << "]\n"
     << "  rotation_rpy_deg: [" << rotation_rpy_deg.x() << ", " << rotation_rpy_deg.y() << ", "
     << rotation_rpy_deg.z() << "]\n"
     << "imu:                               # datasheet (two significant digits)\n"
     << "  rate_hz: " << imu_rate_hz << "\n"
     << "  noise:\n"
     << "    gyro_noise_density: " << gyro_noise_density << "\n"
     << "    accel_noise_density: " << accel_noise_density << "\n"
     << "    gyro_bias_random_walk: " << gyro_bias_random_walk << "\n"
     << "    accel_bias_random_walk: " << accel_bias_random_walk << "\n"
     << "# Clock offset from the synchronisation's calibration (1 ms): a lidar stamp minus the\n"
     << "# IMU stamp of the same instant; subtract it from the lidar stamps.\n"
     << "lidar_time_offset_s: " << lidar_time_offset_s << "\n";
  return os.str();
}

}  // namespace hylo::sim
