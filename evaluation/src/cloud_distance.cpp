#include "hylo/evaluation/cloud_distance.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace hylo::evaluation {
namespace {

double Median(std::vector<double> values) {
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  if (values.size() % 2 == 1) return values[mid];
  const double upper = values[mid];
  const double lower = *std::max_element(values.begin(), values.begin() + mid);
  return 0.5 * (lower + upper);
}

void FillStatistics(const std::vector<double>& distances, CloudDistanceSummary* summary) {
  const double n = static_cast<double>(distances.size());
  double sum = 0.0, sum_sq = 0.0;
  for (double d : distances) {
    sum += d;
    sum_sq += d * d;
    summary->max_m = std::max(summary->max_m, d);
  }
  summary->mean_m = sum / n;
  summary->rms_m = std::sqrt(sum_sq / n);
  // Two-pass variance: the one-pass form loses digits when the mean dominates.
  double sum_dev = 0.0;
  for (double d : distances) sum_dev += (d - summary->mean_m) * (d - summary->mean_m);
  summary->std_m = std::sqrt(sum_dev / n);
  summary->median_m = Median(distances);
}

}  // namespace

bool CloudDistanceOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!(max_distance_m > 0.0) || !std::isfinite(max_distance_m)) {
    os << "max_distance_m = " << max_distance_m << " must be finite and > 0";
  }
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

CloudDistanceSummary CloudToCloudDistance(const PointCloud& cloud,
                                          const registration::NeighborSearch& reference,
                                          const CloudDistanceOptions& options) {
  CloudDistanceSummary summary;
  if (!options.IsValid(&summary.message)) return summary;
  const float range = static_cast<float>(options.max_distance_m);
  std::vector<registration::Neighbor> neighbors;
  std::vector<double> distances;
  distances.reserve(cloud.size());
  for (const Eigen::Vector3f& p : cloud) {
    if (!p.allFinite()) {
      ++summary.num_nonfinite;
      continue;
    }
    ++summary.num_points;
    reference.KNearest(p, 1, range, &neighbors);
    const double d = neighbors.empty()
                         ? options.max_distance_m + 1.0
                         : (neighbors.front().point.cast<double>() - p.cast<double>()).norm();
    if (d > options.max_distance_m) {
      ++summary.num_rejected;
    } else {
      distances.push_back(d);
    }
  }
  summary.count = distances.size();
  if (summary.num_points > 0) {
    summary.rejected_fraction = static_cast<double>(summary.num_rejected) / summary.num_points;
  }
  if (distances.empty()) {
    summary.message = summary.num_points == 0 ? "the cloud has no finite point"
                      : reference.Size() == 0 ? "the reference cloud is empty"
                                              : "no point has a neighbour within max_distance_m";
    return summary;
  }
  FillStatistics(distances, &summary);
  summary.ok = true;
  return summary;
}

}  // namespace hylo::evaluation
