// Path rounding and the speed profile.
#include "route.h"

#include <algorithm>
#include <cmath>

#include "hylo/common/check.h"

namespace hylo::sim {
namespace {

constexpr double kStepM = 0.05;  // dense path spacing, m

void AppendLine(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                std::vector<Eigen::Vector2d>* out) {
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / kStepM)));
  for (int i = 1; i <= n; ++i) out->push_back(a + (b - a) * (double(i) / n));
}

void AppendBezier(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2,
                  std::vector<Eigen::Vector2d>* out) {
  const double approx = (p1 - p0).norm() + (p2 - p1).norm();
  const int n = std::max(2, static_cast<int>(std::ceil(4.0 * approx / kStepM)));
  for (int i = 1; i <= n; ++i) {
    const double u = double(i) / n;
    out->push_back((1 - u) * (1 - u) * p0 + 2 * u * (1 - u) * p1 + u * u * p2);
  }
}

// Resamples a polyline at (nearly) uniform arc length.
std::vector<Eigen::Vector2d> Resample(const std::vector<Eigen::Vector2d>& in) {
  std::vector<Eigen::Vector2d> out{in.front()};
  double carry = 0.0;
  for (size_t i = 1; i < in.size(); ++i) {
    const double seg = (in[i] - in[i - 1]).norm();
    double pos = kStepM - carry;
    while (pos <= seg) {
      out.push_back(in[i - 1] + (in[i] - in[i - 1]) * (pos / seg));
      pos += kStepM;
    }
    carry = seg - (pos - kStepM);
  }
  if ((out.back() - in.back()).norm() > 1e-6) out.push_back(in.back());
  return out;
}

}  // namespace

RoutePlan::RoutePlan(const std::vector<Eigen::Vector2d>& w, const TrajectoryOptions& options) {
  HYLO_CHECK(w.size() >= 2, "a route needs two waypoints");
  std::vector<Eigen::Vector2d> raw{w.front()};
  Eigen::Vector2d cursor = w.front();
  for (size_t i = 1; i + 1 < w.size(); ++i) {
    const double cut = std::min(
        {options.corner_cut_m, 0.45 * (w[i] - w[i - 1]).norm(), 0.45 * (w[i + 1] - w[i]).norm()});
    const Eigen::Vector2d in = w[i] - cut * (w[i] - w[i - 1]).normalized();
    const Eigen::Vector2d out = w[i] + cut * (w[i + 1] - w[i]).normalized();
    AppendLine(cursor, in, &raw);
    AppendBezier(in, w[i], out, &raw);
    cursor = out;
  }
  AppendLine(cursor, w.back(), &raw);
  xy_ = Resample(raw);
  const size_t n = xy_.size();
  s_.assign(n, 0.0);
  heading_.assign(n, 0.0);
  for (size_t i = 1; i < n; ++i) s_[i] = s_[i - 1] + (xy_[i] - xy_[i - 1]).norm();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d d = xy_[std::min(i + 1, n - 1)] - xy_[i > 0 ? i - 1 : 0];
    heading_[i] = std::atan2(d.y(), d.x());
  }
  // Speed limits: cruise, and sqrt(a_lat / curvature) in turns (curvature from the heading
  // change over +-1 m, robust to the discretisation).
  speed_.assign(n, options.cruise_speed_mps);
  const int k = static_cast<int>(std::round(1.0 / kStepM));
  for (size_t i = 0; i < n; ++i) {
    const size_t a = i >= size_t(k) ? i - k : 0, b = std::min(i + k, n - 1);
    const double turn = std::remainder(heading_[b] - heading_[a], 2.0 * M_PI);
    const double curvature = std::abs(turn) / std::max(s_[b] - s_[a], 1e-6);
    if (curvature > 1e-9) {
      const double v_turn = std::sqrt(options.max_lateral_accel_mps2 / curvature);
      speed_[i] = std::min(speed_[i], std::max(v_turn, options.min_turn_speed_mps));
    }
  }
  speed_.front() = speed_.back() = 0.0;
  const double a2 = 2.0 * options.max_accel_mps2;
  for (size_t i = 1; i < n; ++i) {
    speed_[i] =
        std::min(speed_[i], std::sqrt(speed_[i - 1] * speed_[i - 1] + a2 * (s_[i] - s_[i - 1])));
  }
  for (size_t i = n - 1; i-- > 0;) {
    speed_[i] =
        std::min(speed_[i], std::sqrt(speed_[i + 1] * speed_[i + 1] + a2 * (s_[i + 1] - s_[i])));
  }
  t_.assign(n, 0.0);
  for (size_t i = 1; i < n; ++i) {
    t_[i] = t_[i - 1] + 2.0 * (s_[i] - s_[i - 1]) / std::max(speed_[i] + speed_[i - 1], 1e-9);
  }
}

void RoutePlan::Sample(double t_s, Eigen::Vector2d* xy, double* heading, double* speed,
                       double* distance) const {
  const double t = std::clamp(t_s, 0.0, t_.back());
  const size_t hi =
      std::min<size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin(), t_.size() - 1);
  const size_t lo = hi > 0 ? hi - 1 : 0;
  const double span = t_[hi] - t_[lo];
  const double f = span > 0.0 ? (t - t_[lo]) / span : 0.0;
  *xy = xy_[lo] + f * (xy_[hi] - xy_[lo]);
  *heading = heading_[lo] + f * std::remainder(heading_[hi] - heading_[lo], 2.0 * M_PI);
  *speed = t_s >= t_.back() ? 0.0 : speed_[lo] + f * (speed_[hi] - speed_[lo]);
  *distance = s_[lo] + f * (s_[hi] - s_[lo]);
}

}  // namespace hylo::sim
