#include "mechsim/models/nc/slide_drive_data.h"

#include <numbers>

namespace mechsim::models::nc {

namespace {
constexpr double pi = std::numbers::pi;
}

SlideDriveData SlideDriveData::report_cnc200() {
  SlideDriveData data;
  data.slide_inertia_override = 2.1e-4;
  return data;
}

double SlideDriveData::polar_moment() const {
  const double d2 = spindle_diameter * spindle_diameter;
  return pi * d2 * d2 / 32;
}
double SlideDriveData::spindle_inertia() const { return density * polar_moment() * spindle_length; }
double SlideDriveData::spindle_stiffness() const { return shear_modulus * polar_moment() / spindle_length; }
double SlideDriveData::slide_inertia() const {
  if (slide_inertia_override) return *slide_inertia_override;
  const double r = metres_per_radian();
  return slide_mass * r * r;
}
double SlideDriveData::metres_per_radian() const { return lead / (2 * pi); }
double SlideDriveData::coupling_equivalent_length() const {
  return shear_modulus * polar_moment() / coupling_stiffness;
}

}  // namespace mechsim::models::nc
