// The coupling schemes of a connection that crosses a coupling element (`coupling: {scheme,
// stiffness, damping, levels}`, docs/nc-loop.md "Coupling schemes"): the one place that
// names them. A scene's text is parsed once into CouplingScheme (coupling_spec.h); the plan,
// the node types and the tools dispatch on the enum. Pure: no YAML.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mechsim::cosim::coupling {

// compliant: both sides evaluate the spring-damper from their own state and the partner's
// reconstructed angle and speed; torque: the slide side evaluates it and sends the torque;
// interface_jacobian: both blocks take the torque as an input and solve `levels` torque
// levels per macro step from each other's predictions (interface_jacobian.h).
enum class CouplingScheme { compliant, torque, interface_jacobian };

// The scene's words for CouplingScheme, in enum order (what `scheme:` accepts).
const std::vector<std::string>& coupling_scheme_names();
const std::string& to_string(CouplingScheme scheme);
// std::nullopt for a word that names no scheme.
std::optional<CouplingScheme> parse_coupling_scheme(std::string_view name);

// Most torque levels per macro step of the interface-Jacobian scheme: what the
// CouplingPrediction topic carries (idl/coupling.idl).
inline constexpr int kMaxLevels = 16;

}  // namespace mechsim::cosim::coupling
