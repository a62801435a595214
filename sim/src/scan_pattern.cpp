// Firing patterns: spinning heads from their elevation tables and firing slots, and a
// Risley-prism rosette for the Livox-like sensor.
#include "hylo/sim/scan_pattern.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "hylo/common/check.h"
#include "hylo/sim/lidar_model.h"

namespace hylo::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

// A spinning head: elevations in firing order, the time between two slots of a column and
// the azimuth step between columns.
struct Head {
  std::vector<double> elevation_deg;
  int64_t slot_ns = 0;
  double column_deg = 0.2;
};

Head Sixteen(LidarModel model) {
  const BeamTable table = MakeBeamTable(model);
  return {std::vector<double>(table.elevation_deg.begin(), table.elevation_deg.end()),
          table.slot_ns, 0.2};
}

// Channels from the top beam down, evenly spread over `fov_deg` (Ouster OS1: 45 deg).
Head Uniform(int channels, double fov_deg, int64_t slot_ns, double column_deg) {
  Head head;
  for (int i = 0; i < channels; ++i) {
    head.elevation_deg.push_back(0.5 * fov_deg - fov_deg * i / (channels - 1));
  }
  head.slot_ns = slot_ns;
  head.column_deg = column_deg;
  return head;
}

Head HeadOf(SensorKind kind) {
  switch (kind) {
    case SensorKind::kVlp16:
      return Sixteen(LidarModel::kVlp16);
    case SensorKind::kRs16:
      return Sixteen(LidarModel::kRs16);
    case SensorKind::kHesaiXt32:  // +15 .. -16 deg every 1 deg, fired in sequence, 0.18 deg
      return Uniform(32, 31.0, 1512, 0.18);
    case SensorKind::kOuster64:  // every channel of a column fires at once, 1024 columns
      return Uniform(64, 45.0, 0, 360.0 / 1024);
    case SensorKind::kOuster128:
      return Uniform(128, 45.0, 0, 360.0 / 1024);
    case SensorKind::kLivoxRosette:
      break;
  }
  return {};
}

// The revolution of a spinning head turning clockwise seen from above (as the Velodyne,
// RoboSense, Hesai and Ouster heads do), starting at azimuth 180 deg like lidar_model.h's.
std::vector<Shot> Revolution(const Head& head, int64_t period_ns) {
  const int columns = static_cast<int>(std::lround(360.0 / head.column_deg));
  const int channels = static_cast<int>(head.elevation_deg.size());
  HYLO_CHECK(period_ns / columns >= channels * head.slot_ns, "firing sequence exceeds a column");
  std::vector<uint16_t> ring(channels);
  std::vector<Eigen::Vector2d> cos_sin(channels);
  for (int i = 0; i < channels; ++i) {
    ring[i] =
        static_cast<uint16_t>(std::count_if(head.elevation_deg.begin(), head.elevation_deg.end(),
                                            [&](double e) { return e < head.elevation_deg[i]; }));
    cos_sin[i] = {std::cos(head.elevation_deg[i] * kDeg), std::sin(head.elevation_deg[i] * kDeg)};
  }
  std::vector<Shot> shots;
  shots.reserve(static_cast<std::size_t>(columns) * channels);
  for (int c = 0; c < columns; ++c) {
    const int64_t column_ns = c * period_ns / columns;
    for (int s = 0; s < channels; ++s) {
      Shot shot;
      shot.offset_ns = column_ns + s * head.slot_ns;
      const double azimuth = M_PI - 2.0 * M_PI * double(shot.offset_ns) / double(period_ns);
      shot.direction_lidar = Eigen::Vector3d(cos_sin[s].x() * std::cos(azimuth),
                                             cos_sin[s].x() * std::sin(azimuth), cos_sin[s].y());
      shot.ring = ring[s];
      shots.push_back(shot);
    }
  }
  return shots;
}

// The rosette: two prisms turning the beam by kPrismDeg each, at incommensurate rates in
// opposite directions (the deflections add), so the petals never close on themselves; six
// lines fire together, fanned vertically. 24,000 points per 0.1 s frame (Avia-like: a
// 70.4 deg circular field of view, 240 kHz).
constexpr double kPrismDeg = 17.6;
constexpr double kPrismHz[2] = {83.7, -61.3};
constexpr int kLines = 6;
constexpr double kLineSpacingDeg = 0.6;
constexpr int64_t kShotNs = 25'000;

}  // namespace

std::string ToString(SensorKind kind) {
  switch (kind) {
    case SensorKind::kVlp16:
      return "vlp16";
    case SensorKind::kRs16:
      return "rs16";
    case SensorKind::kHesaiXt32:
      return "hesai_xt32";
    case SensorKind::kOuster64:
      return "ouster64";
    case SensorKind::kOuster128:
      return "ouster128";
    case SensorKind::kLivoxRosette:
      return "livox_rosette";
  }
  return "?";
}

std::vector<SensorKind> AllSensorKinds() {
  return {SensorKind::kVlp16,    SensorKind::kRs16,      SensorKind::kHesaiXt32,
          SensorKind::kOuster64, SensorKind::kOuster128, SensorKind::kLivoxRosette};
}

bool ParseSensorKind(const std::string& name, SensorKind* kind) {
  for (const SensorKind k : AllSensorKinds()) {
    if (ToString(k) == name) {
      *kind = k;
      return true;
    }
  }
  return false;
}

SensorSpec SensorSpec::For(SensorKind kind) {
  SensorSpec spec;
  spec.kind = kind;
  switch (kind) {
    case SensorKind::kVlp16:  // the simulator's LidarOptions defaults
      spec.preset = "vlp16";
      spec.time_convention = "velodyne";
      break;
    case SensorKind::kRs16:
      spec.min_range_m = 0.4;
      spec.max_range_m = 150.0;
      spec.preset = "rs16";
      spec.time_convention = "robosense";
      break;
    case SensorKind::kHesaiXt32:
      spec.min_range_m = 0.3;
      spec.max_range_m = 120.0;
      spec.range_noise_m = 0.01;
      spec.preset = "hesai_xt32";
      spec.time_convention = "hesai";
      break;
    case SensorKind::kOuster64:
    case SensorKind::kOuster128:
      spec.min_range_m = 0.5;
      spec.max_range_m = 120.0;
      spec.range_noise_m = 0.015;
      spec.preset = "os1";
      spec.time_convention = "ouster";
      break;
    case SensorKind::kLivoxRosette:
      spec.min_range_m = 1.0;
      spec.max_range_m = 190.0;
      spec.preset = "livox";
      spec.time_convention = "livox";
      break;
  }
  return spec;
}

ScanPattern::ScanPattern(SensorKind kind) : kind_(kind) {
  period_ns_ = std::llround(1e9 / SensorSpec::For(kind).rate_hz);
  if (kind != SensorKind::kLivoxRosette) spinning_ = Revolution(HeadOf(kind), period_ns_);
}

std::size_t ScanPattern::shots_per_frame() const {
  return kind_ == SensorKind::kLivoxRosette
             ? static_cast<std::size_t>(period_ns_ / kShotNs) * kLines
             : spinning_.size();
}

void ScanPattern::Frame(int64_t index, std::vector<Shot>* shots) const {
  if (kind_ == SensorKind::kLivoxRosette) {
    Rosette(index, shots);
  } else {
    *shots = spinning_;
  }
}

void ScanPattern::Rosette(int64_t index, std::vector<Shot>* shots) const {
  shots->clear();
  shots->reserve(shots_per_frame());
  const double prism = kPrismDeg * kDeg;
  for (int64_t offset = 0; offset + kShotNs <= period_ns_; offset += kShotNs) {
    // Seconds since the sensor started; the frame index keeps frames continuous.
    const double t_s = 1e-9 * double(index * period_ns_ + offset);
    const double a1 = 2.0 * M_PI * std::fmod(kPrismHz[0] * t_s, 1.0);
    const double a2 = 2.0 * M_PI * std::fmod(kPrismHz[1] * t_s, 1.0);
    const double u = prism * (std::cos(a1) + std::cos(a2));  // azimuth deflection, rad
    const double v = prism * (std::sin(a1) + std::sin(a2));  // elevation deflection, rad
    for (int line = 0; line < kLines; ++line) {
      const double elevation = v + (line - 0.5 * (kLines - 1)) * kLineSpacingDeg * kDeg;
      Shot shot;
      shot.offset_ns = offset;
      shot.direction_lidar =
          Eigen::Vector3d(std::cos(elevation) * std::cos(u), std::cos(elevation) * std::sin(u),
                          std::sin(elevation));
      shot.ring = static_cast<uint16_t>(line);
      shots->push_back(shot);
    }
  }
}

}  // namespace hylo::sim
