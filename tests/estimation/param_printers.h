#pragma once
// How GoogleTest prints the parameters of the estimation suites: by name, so ctest lists
// "GetParam() = ieskf" instead of the enum's raw bytes. Found by argument-dependent lookup.

#include <ostream>

#include "hylo/estimation/estimator.h"

namespace hylo::estimation {
inline void PrintTo(Estimator::Backend backend, std::ostream* os) { *os << ToString(backend); }
}  // namespace hylo::estimation

