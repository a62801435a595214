#include "hylo/terrain/ground_filter.h"

#include <stdexcept>
#include <utility>

#include "hylo/common/enum_names.h"
#include "hylo/common/option_checks.h"

namespace hylo::terrain {
namespace {

// The fields both back-ends' results share, moved into the common result.
template <class BackEndResult>
GroundFilterResult MoveCommon(GroundMethod method, BackEndResult* r, std::vector<float>* heights) {
  GroundFilterResult result;
  result.method = method;
  result.ok = r->ok;
  result.message = std::move(r->message);
  result.labels = std::move(r->labels);
  result.height_above_ground_m = std::move(*heights);
  result.num_ground = r->num_ground;
  result.num_objects = r->num_objects;
  result.num_invalid = r->num_invalid;
  result.origin_world = r->origin_world;
  return result;
}

// Per back-end: how it runs, where its heights are, what it reports beyond the labels.
ClothFilterResult Run(const std::vector<Eigen::Vector3d>& points_world,
                      const ClothFilterOptions& options, const GroundProgress& progress) {
  return FilterGround(points_world, options, progress);
}
SmrfResult Run(const std::vector<Eigen::Vector3d>& points_world, const SmrfOptions& options,
               const GroundProgress& progress) {
  return FilterGroundSmrf(points_world, options, progress);
}
std::vector<float>* Heights(ClothFilterResult* r) { return &r->height_above_cloth_m; }
std::vector<float>* Heights(SmrfResult* r) { return &r->height_above_surface_m; }

void CopyStats(const ClothFilterResult& cloth, GroundFilterResult* result) {
  CsfStats& s = result->csf;
  s.iterations = cloth.iterations;
  s.converged = cloth.converged;
  s.last_max_displacement_m = cloth.last_max_displacement_m;
  s.cloth_cols = cloth.cloth_cols;
  s.cloth_rows = cloth.cloth_rows;
  s.num_hole_particles = cloth.num_hole_particles;
  s.num_pinned_by_slope = cloth.num_pinned_by_slope;
  s.num_low_outliers = cloth.num_low_outliers;
}
void CopyStats(const SmrfResult& smrf, GroundFilterResult* result) {
  SmrfStats& s = result->smrf;
  s.grid_cols = smrf.grid_cols;
  s.grid_rows = smrf.grid_rows;
  s.num_empty_cells = smrf.num_empty_cells;
  s.num_low_outlier_cells = smrf.num_low_outlier_cells;
  s.num_object_cells = smrf.num_object_cells;
  s.num_readmitted_cells = smrf.num_readmitted_cells;
}

template <class Options, GroundMethod kMethod>
class BackEnd : public GroundFilter {
 public:
  explicit BackEnd(const Options& options) : options_(options) {}
  GroundMethod Method() const override { return kMethod; }

  GroundFilterResult Extract(const std::vector<Eigen::Vector3d>& points_world,
                             const GroundProgress& progress) const override {
    auto split = Run(points_world, options_, progress);
    GroundFilterResult result = MoveCommon(kMethod, &split, Heights(&split));
    CopyStats(split, &result);
    return result;
  }

 private:
  Options options_;
};

}  // namespace

namespace {
constexpr std::pair<GroundMethod, const char*> kGroundMethodNames[] = {
    {GroundMethod::kCsf, "csf"}, {GroundMethod::kSmrf, "smrf"}};
constexpr std::pair<ClothHoleFill, const char*> kHoleFillNames[] = {
    {ClothHoleFill::kNeighbourMean, "mean"},
    {ClothHoleFill::kNearest, "nearest"},
    {ClothHoleFill::kReferenceScanline, "reference"}};
}  // namespace

std::string ToString(GroundMethod method) { return NameOf(kGroundMethodNames, method); }

bool ParseGroundMethod(const std::string& name, GroundMethod* method) {
  return ValueOf(kGroundMethodNames, name, method);
}

std::string ToString(ClothHoleFill fill) { return NameOf(kHoleFillNames, fill); }

bool ParseClothHoleFill(const std::string& name, ClothHoleFill* fill) {
  return ValueOf(kHoleFillNames, name, fill);
}

SmrfOptions LeaveOneOutSmrfOptions() {
  SmrfOptions options;
  options.cell_m = 1.0;
  options.slope = 0.1;
  options.max_window_m = 24.0;
  options.elevation_threshold_m = 0.5;
  options.elevation_scaler = 1.25;
  return options;
}

ClothFilterOptions LeaveOneOutCsfOptions() {
  ClothFilterOptions options;
  options.cloth_resolution_m = 0.5;
  options.rigidness = 6;
  options.hole_fill = ClothHoleFill::kNearest;
  return options;
}

GroundFilterOptions GroundFilterOptions::ForRobotMaps() {
  GroundFilterOptions options;
  options.smrf.elevation_threshold_m = 0.10;
  return options;
}

bool GroundFilterOptions::IsValid(std::string* why) const {
  // Both back-ends' sections: a configuration is valid whichever method it picks.
  return CheckSection(csf, "csf", why) && CheckSection(smrf, "smrf", why);
}

std::unique_ptr<GroundFilter> GroundFilter::Create(const GroundFilterOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  switch (options.method) {
    case GroundMethod::kCsf:
      return std::make_unique<BackEnd<ClothFilterOptions, GroundMethod::kCsf>>(options.csf);
    case GroundMethod::kSmrf:
      return std::make_unique<BackEnd<SmrfOptions, GroundMethod::kSmrf>>(options.smrf);
  }
  throw std::invalid_argument("GroundFilterOptions.method: unknown back-end");
}

GroundFilterResult ExtractGround(const std::vector<Eigen::Vector3d>& points_world,
                                 const GroundFilterOptions& options,
                                 const GroundProgress& progress) {
  return GroundFilter::Create(options)->Extract(points_world, progress);
}

}  // namespace hylo::terrain
