#pragma once
// Robust kernels as iteratively reweighted least squares: a residual r gets the weight
// w(r) = ρ'(r²) of its kernel ρ, fixed for one Gauss-Newton step, so that the weighted step of
// Σ w r² solves Σ ρ(r²) at a fixed point (Zhang, "Parameter estimation techniques", IVC 1997,
// Sec. 5.1; Black and Rangarajan, IJCV 1996). One definition serves every solver of the
// project: the point-to-plane solver (point_to_plane.h) and the sliding window's lidar factors.

#include <string>

namespace hylo::registration {

struct RobustKernel {
  enum class Type {
    kNone,          ///< w = 1: least squares
    kHuber,         ///< w = 1 within the scale, scale/|r| beyond it
    kCauchy,        ///< w = 1 / (1 + r²/s²): large residuals still pull, weakly
    kGemanMcClure,  ///< w = 1 / (1 + r²/s²)²: 1/4 at the scale, ~s⁴/r⁴ far out, so a residual
                    ///< much larger than the scale pulls (almost) nothing
  };
  Type type = Type::kNone;
  double scale_m = 1.0;  ///< residual where the kernel bends, m (> 0)

  static RobustKernel None() { return {}; }
  static RobustKernel Huber(double scale_m) { return {Type::kHuber, scale_m}; }
  static RobustKernel Cauchy(double scale_m) { return {Type::kCauchy, scale_m}; }
  static RobustKernel GemanMcClure(double scale_m) { return {Type::kGemanMcClure, scale_m}; }

  /// The IRLS weight of residual `r_m`, in (0, 1].
  double Weight(double r_m) const {
    switch (type) {
      case Type::kNone:
        return 1.0;
      case Type::kHuber: {
        const double a = r_m < 0.0 ? -r_m : r_m;
        return a <= scale_m ? 1.0 : scale_m / a;
      }
      case Type::kCauchy:
        return 1.0 / (1.0 + (r_m * r_m) / (scale_m * scale_m));
      case Type::kGemanMcClure: {
        const double u = 1.0 + (r_m * r_m) / (scale_m * scale_m);
        return 1.0 / (u * u);
      }
    }
    return 1.0;
  }
};

/// "none", "huber", "cauchy", "geman_mcclure" (configuration files).
std::string ToString(RobustKernel::Type type);
/// Parses those names; false for any other.
bool ParseRobustKernelType(const std::string& name, RobustKernel::Type* type);

}  // namespace hylo::registration
