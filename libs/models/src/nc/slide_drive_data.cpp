#include "mechsim/models/nc/slide_drive_data.h"

#include "mechsim/models/constants.h"

namespace mechsim::models::nc {

SlideDriveData SlideDriveData::report_cnc200() {
  SlideDriveData data;
  data.slide_inertia_override = 2.1e-4;
  return data;
}

namespace {
double circle_polar_moment(double d) { return pi * d * d * d * d / 32; }
}  // namespace

double SlideDriveData::polar_moment() const { return circle_polar_moment(spindle_diameter); }
double SlideDriveData::coupling_piece_polar_moment() const {
  return circle_polar_moment(coupling_piece_diameter.value_or(spindle_diameter));
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
  return shear_modulus * coupling_piece_polar_moment() / coupling_stiffness;
}

}  // namespace mechsim::models::nc
