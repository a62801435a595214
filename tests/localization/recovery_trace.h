#pragma once
// A recovery case's run, scan by scan, for looking into a failure: every scan's status, the
// estimate and the truth (prior map frame, m), the estimated and true speed, the tilt error,
// the scan's fit and its time on the scan path, and every localization event. Written as
// <dir>/s<scenario>_c<case>_<backend>.csv and .events.

#include <string>

#include "localization/recovery_cases.h"

namespace hylo::testing {

/// Writes `run`'s trace under `dir` (created); throws std::runtime_error when it cannot.
void WriteRecoveryTrace(const RecoveryRun& run, const DriveTruth& truth, const std::string& backend,
                        const std::string& dir);

}  // namespace hylo::testing
