#pragma once
// A run configuration as Python holds it: the parsed RunConfig and the YAML text it came from,
// so that a few keys can be changed later (Config.with_overrides) without re-writing the rest.

#include <string>

#include "hylo/config/run_config.h"

namespace hylo::python {

struct ConfigHandle {
  config::RunConfig config;  ///< parsed and validated
  std::string text;          ///< the YAML it was parsed from
  std::string source;        ///< the file or "<dict>", as error messages name it
};

}  // namespace hylo::python
