// The coupling-scheme variants of a scene that `mechsim bench` sweeps (bench.h): the scene
// document with its connections rewritten for each scheme its connections can take.
#pragma once

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace mechsim::bench {

// One coupling-scheme variant of a scene: a name ("jacobi/hold", "interface_jacobian/10")
// and the scene document with its connections rewritten.
struct SchemeVariant {
  std::string name;
  std::string family;     // the curve family: "jacobi", "gauss_seidel", "compliant", "interface_jacobian"
  bool zero_order_hold_jacobi = false;  // the baseline of the 10x target
  bool shipped = false;   // the connections as the scene ships them
  // The scene's orders with every Jacobi edge quadratic ("shipped/quadratic", or the variant
  // with those connections): the adaptive step also runs with it.
  bool shipped_quadratic = false;
  YAML::Node document;
};

// The variants valid for the scene's connections (not yet checked by the scene validator).
std::vector<SchemeVariant> scheme_variants(const YAML::Node& scene_document);

// Equal as data (flow or block style, key order aside): scalars by their text.
bool same_yaml(const YAML::Node& a, const YAML::Node& b);

}  // namespace mechsim::bench
