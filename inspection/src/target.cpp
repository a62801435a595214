#include "hylo/inspection/target.h"

#include <utility>

#include "hylo/common/enum_names.h"
#include "hylo/common/option_checks.h"

namespace hylo::inspection {
namespace {

constexpr std::pair<TargetStatus, const char*> kStatusNames[] = {
    {TargetStatus::kPlanned, "planned"},
    {TargetStatus::kOccluded, "occluded"},
    {TargetStatus::kUnreachable, "unreachable"},
};

// NaN is allowed (the default applies); anything else must be finite and > 0.
bool CheckOptionalPositive(const char* field, double value, std::string* why) {
  return std::isnan(value) || CheckPositive(field, value, why);
}

}  // namespace

const char* TargetStatusName(TargetStatus status) {
  for (const auto& [value, name] : kStatusNames) {
    if (value == status) return name;
  }
  return "unknown";
}

bool Target::IsValid(std::string* why) const {
  if (id.empty()) return FailOption("id", "''", "must not be empty", why);
  if (!position.allFinite())
    return FailOption("position", position.transpose(), "must be finite", why);
  if (!CheckOptionalPositive("min_range_m", min_range_m, why) ||
      !CheckOptionalPositive("max_range_m", max_range_m, why)) {
    return false;
  }
  if (std::isfinite(min_range_m) && std::isfinite(max_range_m) && min_range_m >= max_range_m)
    return FailOption("min_range_m", min_range_m, "must be < max_range_m", why);
  if (!box_size_m.allFinite() || (box_size_m.array() < 0.0).any())
    return FailOption("box_size_m", box_size_m.transpose(), "must be finite and >= 0", why);
  if (std::isnan(view_azimuth_deg) != std::isnan(view_tolerance_deg))
    return FailOption("view_tolerance_deg", view_tolerance_deg,
                      "view_azimuth_deg and view_tolerance_deg go together", why);
  if (!std::isnan(view_azimuth_deg)) {
    return CheckInRange("view_azimuth_deg", view_azimuth_deg, -360.0, 360.0, why) &&
           (view_tolerance_deg > 0.0 ||
            FailOption("view_tolerance_deg", view_tolerance_deg, "must be in (0, 180]", why)) &&
           CheckInRange("view_tolerance_deg", view_tolerance_deg, 0.0, 180.0, why);
  }
  return true;
}

}  // namespace hylo::inspection
