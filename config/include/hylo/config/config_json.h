#pragma once
// Option structs as JSON, written by the same field list as the YAML (run_config_fields.h), so
// a summary records every setting under the key a configuration file uses: a field added to
// the list appears in every JSON that records its section.

#include "hylo/config/run_config.h"
#include "hylo/io/json.h"

namespace hylo::config {

/// Every section and key of the run configuration; enums by name, `imu: none` as "none",
/// infinite values as null.
io::Json ToJson(const RunConfig& config);
/// The `ground` section alone, and each of its back-ends (`ground.csf`, `ground.smrf`).
io::Json ToJson(const terrain::GroundFilterOptions& options);
io::Json ToJson(const terrain::ClothFilterOptions& options);
io::Json ToJson(const terrain::SmrfOptions& options);

}  // namespace hylo::config
