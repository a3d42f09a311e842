#include "graspmix/core/frame_jitter.hpp"

#include <cmath>

namespace graspmix {

double frame_jitter_angle(double anisotropy, double sharpness, double u) {
  constexpr double kPi = 3.14159265358979323846;
  // Evaluated as (u * pi) * exp(...): the order both callers have always used.
  return u * kPi * std::exp(-sharpness * anisotropy * anisotropy);
}

}  // namespace graspmix
