#include "mechsim/catalog/coupling/coupling_spec.h"

#include "mechsim/config/units.h"

namespace mechsim::cosim::coupling {

CouplingSpec parse_coupling(const config::ConfigNode& c) {
  namespace dim = config::dim;
  c.allow_only({"scheme", "stiffness", "damping", "levels"});
  CouplingSpec spec;
  // choice_or refuses any other word, listing the names; what it returns always parses.
  spec.scheme = *parse_coupling_scheme(c.choice_or("scheme", coupling_scheme_names(), to_string(CouplingScheme::compliant)));
  spec.params.stiffness = c.positive_quantity("stiffness", dim::torsional_stiffness);
  spec.params.damping = c.non_negative_quantity_or("damping", dim::rotational_damping, 0.0);
  if (c.has("levels")) {
    if (spec.scheme != CouplingScheme::interface_jacobian)
      c.child("levels").fail("expected 'levels' only with scheme: " + to_string(CouplingScheme::interface_jacobian));
    spec.levels = static_cast<int>(c.integer("levels"));
    if (spec.levels < 1 || spec.levels > kMaxLevels)
      c.child("levels").fail("expected a number of torque levels per macro step in 1.." + std::to_string(kMaxLevels));
  }
  return spec;
}

}  // namespace mechsim::cosim::coupling
