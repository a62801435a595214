#pragma once
// The offline mapping chain as file-to-file steps (Alamanos et al., Sec. IV): craft a raw
// map (uniform sampling + MLS), split ground from objects (SMRF or cloth simulation), build the
// traversability grid map and costmap. Used by `hylo demo`; `hylo craft`, `hylo ground` and
// `hylo traversability` do the same work with every option exposed.
// Each step throws std::runtime_error naming the file and the reason when it cannot go on.

#include <array>
#include <string>
#include <vector>

#include "hylo/io/json.h"
#include "hylo/terrain/ground_filter.h"
#include "hylo/terrain/craft.h"
#include "hylo/terrain/traversability.h"

namespace hylo::cli {

struct CraftStep {
  std::size_t input_points = 0;   ///< points read
  std::size_t output_points = 0;  ///< points written
  double seconds = 0.0;           ///< sampling + MLS wall time, s
  io::Json ToJson() const;
};
/// `in_path` (raw map) -> `out_path` (crafted map with normals).
CraftStep CraftFile(const std::string& in_path, const std::string& out_path,
                    const terrain::CraftOptions& options);

struct GroundStep {
  std::string method;  ///< the ground back-end that ran (smrf | csf)
  std::size_t ground_points = 0, object_points = 0;
  double seconds = 0.0;  ///< wall time, s
  io::Json ToJson() const;
};
/// `in_path` -> ground and object clouds (every attribute of the input kept).
GroundStep GroundFile(const std::string& in_path, const std::string& ground_path,
                      const std::string& objects_path,
                      const terrain::GroundFilterOptions& options);

struct TraversabilityStep {
  std::array<std::size_t, terrain::kNumCellClasses> cells{};  ///< per terrain::CellClass
  double resolution_m = 0.0;
  int width = 0, height = 0;  ///< grid size, cells
  terrain::SlopeStats slope;
  std::vector<std::string> files;  ///< written: costmap.yaml/.pgm/.png, layers/*.asc
  double seconds = 0.0;
  io::Json ToJson() const;
};
/// Ground (+ objects) clouds -> grid map layers and costmap files in `out_dir`.
TraversabilityStep TraversabilityFiles(const std::string& ground_path,
                                       const std::string& objects_path, const std::string& out_dir,
                                       const terrain::TraversabilityOptions& options);

}  // namespace hylo::cli
