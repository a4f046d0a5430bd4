#include "mechsim/catalog/coupling/scheme.h"

#include <algorithm>

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

}  // namespace mechsim::cosim::coupling
