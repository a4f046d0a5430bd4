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

std::string missing_state_capabilities(const ModelDescription& md, InterfaceKind kind) {
  const Interface* i = md.find_interface(kind);
  if (i == nullptr) return "";
  const bool v2 = md.version == FmiVersion::fmi2;
  std::string missing;
  if (!i->can_get_and_set_state) missing = v2 ? "canGetAndSetFMUstate" : "canGetAndSetFMUState";
  if (!i->can_serialize_state)
    missing += std::string(missing.empty() ? "" : " and ") + (v2 ? "canSerializeFMUstate" : "canSerializeFMUState");
  return missing;
}

void FmuInstance::require_state_capability(const char* what) const {
  if (!missing_state_.empty())
    throw FmuError(label_, std::string("cannot ") + what + " its state: its " + std::string(to_string(kind_)) +
                               " interface does not declare " + missing_state_);
}

}  // namespace mechsim::fmi
