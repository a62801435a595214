#pragma once
// `hylo demo`'s inspection step: the simulated site's equipment (sim/equipment_targets.h) as
// targets in the crafted map's frame, and `hylo inspect`'s plan for them from the start of
// session A (the map frame's origin), written as `hylo inspect` writes it.

#include <string>

#include "hylo/evaluation/trajectory_metrics.h"
#include "hylo/io/json.h"
#include "hylo/sim/site_layout.h"

namespace hylo::cli {

struct InspectionStep {
  std::string dir;          ///< the plan's files (plan.csv, route.csv, plan.png, ...)
  std::string targets_csv;  ///< the targets given, map frame
  io::Json plan;            ///< the plan's summary.json (counts, route, per target)
  double seconds = 0.0;     ///< wall time of the step (reading, planning, writing), s
  io::Json ToJson() const;  ///< counts, route, timings and the targets not planned
};

/// Writes the targets of session A's equipment (site frame taken into the map frame with the
/// inverse of `ate_a`, A's alignment map -> truth) to `dir`/targets.csv and plans them on
/// `crafted_map` and `costmap_dir`. Throws std::runtime_error when a step cannot go on.
InspectionStep InspectSite(const sim::Site& site, const evaluation::AteResult& ate_a,
                           const std::string& crafted_map, const std::string& costmap_dir,
                           const std::string& dir);

}  // namespace hylo::cli
