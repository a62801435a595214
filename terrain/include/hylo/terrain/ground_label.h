#pragma once
// The per-point answer of every ground back-end (cloth simulation, SMRF).

#include <cstdint>

namespace hylo::terrain {

enum class GroundLabel : uint8_t {
  kGround = 0,   ///< on the terrain surface the back-end estimated
  kObject = 1,   ///< off it (buildings, vegetation, noise above or below the ground)
  kInvalid = 2,  ///< non-finite input point, not classified
};

}  // namespace hylo::terrain
