#pragma once
// Inspection targets on disk, in the map frame (the crafted map's and the costmap's).
//
// CSV: '#' comment lines and blank lines anywhere; the first other line is the header, which
// names the columns in any order: id, x, y, z (required), and optionally min_range_m,
// max_range_m, size_x, size_y, size_z (all three: an axis-aligned box), view_azimuth_deg and
// view_tolerance_deg (both: the camera must stand within the tolerance of this direction as
// seen from the target, counter-clockwise from east). An empty optional cell takes the
// planner's default. Example:
//   id,x,y,z,view_azimuth_deg,view_tolerance_deg
//   bushing_T1,36.0,55.6,4.2,270,60
// YAML: the same keys, one map per target, under `targets:` (or a bare list):
//   targets:
//     - {id: bushing_T1, x: 36.0, y: 55.6, z: 4.2}
//     - {id: tank_T2, x: 52, y: 55, z: 1.8, size_x: 5, size_y: 3, size_z: 3}
// Ids are letters, digits, '_', '-' and '.', start with a letter, digit or '_', at most 64
// characters (each names a file of `hylo inspect`), and are unique.

#include <string>
#include <vector>

#include "hylo/inspection/target.h"

namespace hylo::io {

/// Reads a targets file, CSV or YAML by its extension (.csv, .yaml, .yml). Throws
/// std::runtime_error with one line naming the file, the line (and column) and the reason:
/// unreadable file, unknown or missing column or key, a value that is not a finite number,
/// an invalid or repeated id, an invalid target (inspection::Target::IsValid), no target.
std::vector<inspection::Target> ReadTargets(const std::string& path);
std::vector<inspection::Target> ReadTargetsCsv(const std::string& path);
std::vector<inspection::Target> ReadTargetsYaml(const std::string& path);

/// Writes targets as CSV (every column; defaults as empty cells), atomically. Throws
/// std::runtime_error naming the file when it cannot be written.
void WriteTargetsCsv(const std::string& path, const std::vector<inspection::Target>& targets);

/// True when `id` is usable as a target id (see the file comment).
bool IsValidTargetId(const std::string& id);

}  // namespace hylo::io
