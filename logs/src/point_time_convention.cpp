#include "hylo/logs/log_reader.h"

namespace hylo::logs {

std::string ToString(PointTimeConvention convention) {
  switch (convention) {
    case PointTimeConvention::kAuto: return "auto";
    case PointTimeConvention::kVelodyne: return "velodyne";
    case PointTimeConvention::kOuster: return "ouster";
    case PointTimeConvention::kHesai: return "hesai";
    case PointTimeConvention::kRobosense: return "robosense";
    case PointTimeConvention::kLivox: return "livox";
    case PointTimeConvention::kNone: return "none";
  }
  return "unknown";
}

bool ParsePointTimeConvention(const std::string& name, PointTimeConvention* convention) {
  for (auto c : {PointTimeConvention::kAuto, PointTimeConvention::kVelodyne,
                 PointTimeConvention::kOuster, PointTimeConvention::kHesai,
                 PointTimeConvention::kRobosense, PointTimeConvention::kLivox,
                 PointTimeConvention::kNone}) {
    if (ToString(c) == name) {
      *convention = c;
      return true;
    }
  }
  return false;
}

}  // namespace hylo::logs
