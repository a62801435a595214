#include "hylo/mapping/craft.h"

#include <chrono>
#include <sstream>
#include <stdexcept>

#include "hylo/mapping/craft_mls.h"
#include "hylo/mapping/local_origin.h"
#include "hylo/registration/voxel_filter.h"

namespace hylo::mapping {
namespace {

template <typename T>
bool Fail(std::string* why, const char* field, T value, const char* constraint) {
  if (why != nullptr) {
    std::ostringstream os;
    os << "CraftOptions." << field << " = " << value << ": must be " << constraint;
    *why = os.str();
  }
  return false;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

bool CraftOptions::IsValid(std::string* why) const {
  if (!(voxel_size_m >= 0.0)) return Fail(why, "voxel_size_m", voxel_size_m, ">= 0");
  if (!(mls_search_radius_m > 0.0)) {
    return Fail(why, "mls_search_radius_m", mls_search_radius_m, "> 0");
  }
  if (polynomial_order < 0 || polynomial_order > 3) {
    return Fail(why, "polynomial_order", polynomial_order, "in [0, 3]");
  }
  if (num_threads < 1) return Fail(why, "num_threads", num_threads, ">= 1");
  return true;
}

CraftResult CraftMap(const std::vector<Eigen::Vector3d>& points_world,
                     const CraftOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  CraftResult result;
  result.num_input = points_world.size();
  result.origin_world = ChooseOrigin(points_world);
  registration::PointCloud local;
  local.reserve(points_world.size());
  for (const Eigen::Vector3f& p : ToLocal(points_world, result.origin_world)) {
    if (p.allFinite())
      local.push_back(p);
    else
      ++result.num_invalid;
  }
  if (local.empty()) {
    result.message = points_world.empty() ? "empty cloud" : "no finite point in the cloud";
    return result;
  }
  auto start = std::chrono::steady_clock::now();
  const registration::PointCloud sampled =
      registration::UniformSample(local, static_cast<float>(options.voxel_size_m));
  result.sampling_seconds = SecondsSince(start);
  result.num_sampled = sampled.size();

  start = std::chrono::steady_clock::now();
  MlsOutput smoothed = SmoothMls(sampled, options.mls_search_radius_m, options.polynomial_order,
                                 options.num_threads, options.compute_normals);
  result.mls_seconds = SecondsSince(start);
  result.num_dropped_by_mls = sampled.size() - smoothed.points.size();
  result.points_world = ToWorld(smoothed.points, result.origin_world);
  result.normals = std::move(smoothed.normals);
  result.ok = !result.points_world.empty();
  std::ostringstream os;
  os << result.num_input << " in, " << result.num_sampled << " after sampling, "
     << result.points_world.size() << " out";
  if (!result.ok) os << ": no point had enough neighbours within the MLS radius";
  result.message = os.str();
  return result;
}

}  // namespace hylo::mapping
