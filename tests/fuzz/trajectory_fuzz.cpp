// Fuzz target: trajectory files. The first byte picks the reader: TUM, KITTI (stamps from a
// period), KITTI with a times file, or a times file alone; for KITTI with times the rest is
// "<poses>\n%%\n<times>".

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "hylo/io/trajectory_io.h"

namespace {

using hylo::fuzz::Require;
using hylo::io::StampedPose;

void CheckPoses(const std::vector<StampedPose>& poses) {
  for (const StampedPose& p : poses) {
    Require(p.position.allFinite(), "a non-finite position was accepted");
    Require(std::abs(p.orientation.norm() - 1.0) < 1e-9, "orientation is not a unit quaternion");
  }
}

// Stamps go back to text and return unchanged (what WriteTum/WriteKitti rely on).
void CheckStamp(int64_t t_ns) {
  int64_t again = 0;
  const std::string text = hylo::io::FormatNsAsSeconds(t_ns);
  Require(hylo::io::ParseSecondsToNs(text, &again) && again == t_ns,
          "stamp " + std::to_string(t_ns) + " does not survive '" + text + "'");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const int mode = data[0] % 4;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  const std::vector<std::string> parts = hylo::fuzz::Split(text, "\n%%\n");
  const std::string poses_path = hylo::fuzz::WriteScratchFile("poses.txt", parts[0]);
  const std::string times_path =
      hylo::fuzz::WriteScratchFile("times.txt", parts.size() > 1 ? parts[1] : parts[0]);
  try {
    std::vector<StampedPose> poses;
    if (mode == 0) {
      poses = hylo::io::ReadTum(poses_path);
    } else if (mode == 1) {
      poses = hylo::io::ReadKitti(poses_path);
    } else if (mode == 2) {
      hylo::io::KittiTiming timing;
      timing.times_path = times_path;
      poses = hylo::io::ReadKitti(poses_path, timing);
    } else {
      for (const int64_t t_ns : hylo::io::ReadTimes(times_path)) CheckStamp(t_ns);
    }
    CheckPoses(poses);
    for (const StampedPose& p : poses) CheckStamp(p.t_ns);
  } catch (const std::runtime_error& e) {
    // KITTI with times names whichever of the two files is at fault.
    if (mode == 2) {
      hylo::fuzz::RequireClearError(e, std::vector<std::string>{poses_path, times_path});
    } else {
      hylo::fuzz::RequireClearError(e, mode == 3 ? times_path : poses_path);
    }
  }
  return 0;
}
