#pragma once
// A worker's priority below the thread that starts it (Linux: threads have their own
// niceness). Relative, not absolute: in a process started with `nice -n 19` by a privileged
// user an absolute value would raise the worker above the scan thread. Best effort.

namespace hylo::localization {

/// The calling thread's niceness (0 when it cannot be read).
int ThisThreadsNiceness();
/// Sets the calling thread's niceness to `starter_niceness + steps_below`, capped at 19.
void LowerThisThreadsPriority(int starter_niceness, int steps_below);

}  // namespace hylo::localization
