#include "thread_niceness.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

namespace hylo::localization {
namespace {

constexpr int kMaxNiceness = 19;

id_t ThisThreadsId() { return static_cast<id_t>(syscall(SYS_gettid)); }

}  // namespace

int ThisThreadsNiceness() {
  errno = 0;  // getpriority may return -1 as a niceness
  const int niceness = getpriority(PRIO_PROCESS, ThisThreadsId());
  return errno == 0 ? niceness : 0;
}

void LowerThisThreadsPriority(int starter_niceness, int steps_below) {
  setpriority(PRIO_PROCESS, ThisThreadsId(),
              std::min(starter_niceness + steps_below, kMaxNiceness));
}

}  // namespace hylo::localization
