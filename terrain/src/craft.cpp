#include "hylo/terrain/craft.h"

#include <chrono>
#include <cstdint>
#include <sstream>
#include <stdexcept>

#include "hylo/common/local_origin.h"
#include "hylo/registration/voxel_filter.h"
#include "hylo/terrain/craft_mls.h"

namespace hylo::terrain {
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

// The MLS data: the sampled points (the queries) plus, when the support voxel is finer than the
// sampling voxel, the input thinned to one point per support voxel; each point once, in input
// order. `queries` receives the sampled points' positions in the returned cloud.
PointCloud MlsSupport(const PointCloud& local, const std::vector<std::size_t>& sampled,
                      const CraftOptions& options, std::vector<std::size_t>* queries) {
  enum : uint8_t { kSupport = 1, kQuery = 2 };
  std::vector<uint8_t> role(local.size(), 0);
  for (const std::size_t i : sampled) role[i] = kQuery;
  if (options.voxel_size_m > 0.0 && options.mls_support_voxel_m < options.voxel_size_m) {
    // A support voxel of 0 keeps every point (UniformSampleIndices returns them all).
    const float voxel = static_cast<float>(options.mls_support_voxel_m);
    for (const std::size_t i : registration::UniformSampleIndices(local, voxel)) {
      role[i] |= kSupport;
    }
  }
  PointCloud support;
  queries->clear();
  for (std::size_t i = 0; i < local.size(); ++i) {
    if (role[i] & kQuery) queries->push_back(support.size());
    if (role[i] != 0) support.push_back(local[i]);
  }
  return support;
}

}  // namespace

bool CraftOptions::IsValid(std::string* why) const {
  if (!(voxel_size_m >= 0.0)) return Fail(why, "voxel_size_m", voxel_size_m, ">= 0");
  if (!(mls_search_radius_m > 0.0)) {
    return Fail(why, "mls_search_radius_m", mls_search_radius_m, "> 0");
  }
  if (!(mls_support_voxel_m >= 0.0)) {
    return Fail(why, "mls_support_voxel_m", mls_support_voxel_m, ">= 0");
  }
  if (!(mls_small_radius_m >= 0.0 && mls_small_radius_m < mls_search_radius_m)) {
    return Fail(why, "mls_small_radius_m", mls_small_radius_m, "in [0, mls_search_radius_m)");
  }
  if (!(scale_consistency_sigmas > 0.0)) {
    return Fail(why, "scale_consistency_sigmas", scale_consistency_sigmas, "> 0");
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
  PointCloud local;
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
  // A voxel of 0 keeps every point (UniformSampleIndices returns them all).
  const std::vector<std::size_t> sampled =
      registration::UniformSampleIndices(local, static_cast<float>(options.voxel_size_m));
  result.sampling_seconds = SecondsSince(start);
  result.num_sampled = sampled.size();

  start = std::chrono::steady_clock::now();
  std::vector<std::size_t> queries;
  const PointCloud support = MlsSupport(local, sampled, options, &queries);
  result.num_support = support.size();
  MlsSettings mls;
  mls.search_radius_m = options.mls_search_radius_m;
  mls.small_radius_m = options.mls_small_radius_m;
  mls.consistency_sigmas = options.scale_consistency_sigmas;
  mls.polynomial_order = options.polynomial_order;
  mls.num_threads = options.num_threads;
  mls.compute_normals = options.compute_normals;
  MlsOutput smoothed = SmoothMls(support, queries, mls);
  result.mls_seconds = SecondsSince(start);
  result.num_small_scale = smoothed.num_small_scale;
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

}  // namespace hylo::terrain
