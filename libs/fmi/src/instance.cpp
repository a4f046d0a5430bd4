#include "mechsim/fmi/instance.h"

#include <cmath>
#include <cstdio>

#include "versioned_instances.h"

namespace mechsim::fmi {

std::unique_ptr<FmuInstance> FmuInstance::create(const FmuArchive& archive, InterfaceKind kind,
                                                 const std::string& instance_name) {
  if (archive.description().version == FmiVersion::fmi2) return make_fmi2_instance(archive, kind, instance_name);
  return make_fmi3_instance(archive, kind, instance_name);
}

double FmuInstance::get_finite_real(const Variable& v) {
  const double value = get_real(v.value_reference);
  if (std::isfinite(value)) return value;
  char when[64];
  std::snprintf(when, sizeof when, "%.9g", time_);
  throw FmuError(label_, "output '" + v.name + "' is " + (std::isnan(value) ? "NaN" : "infinite") + " at t = " +
                             when + " s");
}

}  // namespace mechsim::fmi
