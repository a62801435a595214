#include "hylo/terrain/ground_smrf_dem.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hylo/common/check.h"
#include "hylo/terrain/ground_smrf_inpaint.h"

namespace hylo::terrain::smrf {
namespace {

bool HasPoint(const Raster& minimum, std::size_t i) { return !std::isnan(minimum.z[i]); }

// The DEM through the ground cells' heights, every other cell filled.
Raster Fill(const Raster& heights, const std::vector<uint8_t>& ground) {
  Raster dem = heights;
  for (std::size_t i = 0; i < ground.size(); ++i) {
    if (!ground[i]) dem.z[i] = std::numeric_limits<float>::quiet_NaN();
  }
  InpaintTangentPlanes(&dem);
  return dem;
}

// Each cell's lowest point moved to the cell centre along the plane of `dem` there.
Raster Centred(const DemInput& in, const Raster& dem) {
  Raster centred = *in.minimum;
  for (int row = 0; row < dem.rows; ++row) {
    for (int col = 0; col < dem.cols; ++col) {
      const std::size_t i = dem.Index(col, row);
      if (!HasPoint(centred, i)) continue;
      const Eigen::Vector2d rise_per_m = GradientPerCell(dem, col, row) / dem.cell_m;
      centred.z[i] -= static_cast<float>(rise_per_m.dot((*in.lowest_offset_m)[i].cast<double>()));
    }
  }
  return centred;
}

}  // namespace

Dem BuildDem(const DemInput& in) {
  HYLO_CHECK(in.minimum && in.lowest_offset_m && in.low_outlier && in.object, "every input");
  const Raster& minimum = *in.minimum;
  const std::size_t size = minimum.Size();
  HYLO_CHECK(in.lowest_offset_m->size() == size && in.low_outlier->size() == size &&
                 in.object->size() == size,
             "one value per cell");
  Dem dem;
  dem.ground.assign(size, 0);
  bool any = false;
  for (std::size_t i = 0; i < size; ++i) {
    dem.ground[i] = HasPoint(minimum, i) && !(*in.low_outlier)[i] && !(*in.object)[i];
    any = any || dem.ground[i];
  }
  const bool all_flagged = !any;
  if (all_flagged) {
    for (std::size_t i = 0; i < size; ++i) dem.ground[i] = HasPoint(minimum, i);
  }
  dem.z = Fill(minimum, dem.ground);
  dem.rounds = 1;
  while (dem.rounds < kMaxDemRounds) {
    const Raster centred = Centred(in, dem.z);
    std::size_t admitted = 0;
    for (std::size_t i = 0; i < size && !all_flagged; ++i) {
      if (dem.ground[i] || !HasPoint(minimum, i) || (*in.low_outlier)[i]) continue;
      if (std::abs(centred.z[i] - dem.z.z[i]) <= in.readmit_within_m) {
        dem.ground[i] = 1;
        ++admitted;
      }
    }
    dem.num_readmitted_cells += admitted;
    dem.z = Fill(centred, dem.ground);
    ++dem.rounds;
    if (admitted == 0) break;
  }
  return dem;
}

}  // namespace hylo::terrain::smrf
