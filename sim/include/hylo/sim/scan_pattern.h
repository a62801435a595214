#pragma once
// Where a lidar fires within one frame: the shot directions in the lidar frame, their time
// offsets from the frame start and their ring (channel). Spinning heads repeat the same
// pattern every revolution (VLP-16 and RS-16 from lidar_model.h's beam tables, a 32-channel
// Hesai XT32-like head, 64- and 128-channel Ouster OS1-like heads); a Livox-like sensor
// draws a non-repetitive rosette with two counter-rotating prisms, so every frame is
// different and the pattern only fills its field of view over time.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace hylo::sim {

enum class SensorKind { kVlp16, kRs16, kHesaiXt32, kOuster64, kOuster128, kLivoxRosette };
/// "vlp16", "rs16", "hesai_xt32", "ouster64", "ouster128", "livox_rosette".
std::string ToString(SensorKind kind);
bool ParseSensorKind(const std::string& name, SensorKind* kind);
/// Every kind, in enum order.
std::vector<SensorKind> AllSensorKinds();

/// One laser shot of a frame.
struct Shot {
  int64_t offset_ns = 0;                                       ///< after the frame start, ns
  Eigen::Vector3d direction_lidar = Eigen::Vector3d::UnitX();  ///< unit, lidar frame
  uint16_t ring = 0;  ///< channel, 0 = lowest elevation (Livox: the line)
};

/// What a datasheet says about the sensor, and how its driver publishes it.
struct SensorSpec {
  SensorKind kind = SensorKind::kVlp16;
  double rate_hz = 10.0;              ///< frames per second, Hz
  double min_range_m = 0.8;           ///< closer returns are lost, m
  double max_range_m = 100.0;         ///< farther surfaces give no return, m
  double range_noise_m = 0.02;        ///< 1-sigma range noise, m
  double dropout_probability = 0.01;  ///< random missing returns, [0, 1)
  double min_incidence_cos = 0.03;    ///< grazing returns below this cosine are lost
  std::string preset;                 ///< the driver's configuration preset (config/presets/)
  std::string time_convention;        ///< the driver's per-point time field (io names)

  /// The datasheet figures of `kind` (range noise is the nominal 1 sigma).
  static SensorSpec For(SensorKind kind);
};

class ScanPattern {
 public:
  explicit ScanPattern(SensorKind kind);

  /// The shots of frame `index` (frames follow each other without gaps), in firing order.
  void Frame(int64_t index, std::vector<Shot>* shots) const;
  int64_t period_ns() const { return period_ns_; }
  SensorKind kind() const { return kind_; }
  /// Shots per frame (the same for every frame).
  std::size_t shots_per_frame() const;

 private:
  void Rosette(int64_t index, std::vector<Shot>* shots) const;

  SensorKind kind_;
  int64_t period_ns_ = 100'000'000;
  std::vector<Shot> spinning_;  // the revolution of a spinning head (empty for the rosette)
};

}  // namespace hylo::sim
