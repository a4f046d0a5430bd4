#include "mechsim/cosim/coupling/scheme.h"

#include <algorithm>

#include "mechsim/config/units.h"
#include "mechsim/cosim/coupling/interface_jacobian.h"

namespace mechsim::cosim::coupling {

const std::vector<std::string>& coupling_scheme_names() {
  static const std::vector<std::string> names{"compliant", "torque", "interface_jacobian"};
  return names;
}

const std::string& to_string(CouplingScheme scheme) { return coupling_scheme_names().at(static_cast<std::size_t>(scheme)); }

std::optional<CouplingScheme> parse_coupling_scheme(std::string_view name) {
  const auto& names = coupling_scheme_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) return std::nullopt;
  return static_cast<CouplingScheme>(it - names.begin());
}

CouplingSpec parse_coupling(const config::ConfigNode& c) {
  namespace dim = config::dim;
  c.allow_only({"scheme", "stiffness", "damping", "levels"});
  CouplingSpec spec;
  // choice_or refuses any other word with the list; what it returns always parses.
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
