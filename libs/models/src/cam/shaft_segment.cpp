#include "mechsim/models/cam/shaft_segment.h"

#include <cmath>
#include <stdexcept>

namespace mechsim::models::cam {

void validate(const ShaftSegment& segment) {
  if (!(segment.stiffness > 0.0 && std::isfinite(segment.stiffness)))
    throw std::invalid_argument("shaft segment: the stiffness must be finite and > 0");
  if (!(segment.damping >= 0.0 && std::isfinite(segment.damping)))
    throw std::invalid_argument("shaft segment: the damping must be finite and >= 0");
}

}  // namespace mechsim::models::cam
