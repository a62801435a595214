#include "hylo/registration/robust_kernel.h"

#include <utility>

#include "hylo/common/enum_names.h"

namespace hylo::registration {
namespace {

using Type = RobustKernel::Type;
const std::pair<Type, const char*> kNames[] = {{Type::kNone, "none"},
                                                {Type::kHuber, "huber"},
                                                {Type::kCauchy, "cauchy"},
                                                {Type::kGemanMcClure, "geman_mcclure"}};

}  // namespace

std::string ToString(RobustKernel::Type type) { return NameOf(kNames, type); }

bool ParseRobustKernelType(const std::string& name, RobustKernel::Type* type) {
  return ValueOf(kNames, name, type);
}

}  // namespace hylo::registration
