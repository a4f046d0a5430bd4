#include "scheme_variants.h"

#include <algorithm>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include "mechsim/catalog/coupling/scheme.h"

namespace mechsim::bench {

using cosim::coupling::CouplingScheme;
using cosim::coupling::to_string;

// Equal as data (flow or block style, key order aside): scalars by their text.
bool same_yaml(const YAML::Node& a, const YAML::Node& b) {
  if (a.Type() != b.Type()) return false;
  if (a.IsScalar()) return a.Scalar() == b.Scalar();
  if (a.IsSequence()) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!same_yaml(a[i], b[i])) return false;
    return true;
  }
  if (a.IsMap()) {
    if (a.size() != b.size()) return false;
    for (const auto& kv : a) {
      const YAML::Node other = b[kv.first.Scalar()];
      if (!other || !same_yaml(kv.second, other)) return false;
    }
    return true;
  }
  return true;  // both null
}

namespace {

YAML::Node connection(const std::string& from, const std::string& to) {
  YAML::Node c(YAML::NodeType::Map);
  c["from"] = from;
  c["to"] = to;
  return c;
}

// The text of `key` in `n`, or `def` without it.
std::string text_of(const YAML::Node& n, const char* key, const std::string& def = "") {
  return n[key] ? n[key].as<std::string>() : def;
}

// The scene's own orders with every Jacobi edge extrapolated quadratically: under an
// error-controlled step the predictor's order buys longer steps (docs/accuracy.md, "The
// predictor's order and the node solvers' floor"), where at a fixed H the scene's lower
// order may be the better one. None where it changes nothing.
std::optional<YAML::Node> quadratic_connections_of(const YAML::Node& scene_document) {
  YAML::Node doc = YAML::Clone(scene_document);
  bool changed = false;
  for (auto c : doc["connections"]) {
    const bool jacobi = text_of(c, "order", "jacobi") == "jacobi";
    const YAML::Node& edge = c;  // const: operator[] must not add keys
    const bool interface_jacobian = edge["coupling"] && cosim::coupling::parse_coupling_scheme(text_of(edge["coupling"], "scheme")) == CouplingScheme::interface_jacobian;
    if (!jacobi || interface_jacobian || text_of(c, "reconstruction", "hold") == "quadratic") continue;
    c["reconstruction"] = "quadratic";
    changed = true;
  }
  if (!changed) return std::nullopt;
  return doc["connections"];
}

// Appends the quadratic variant of the shipped orders or, where another variant has the
// same connections, marks that one instead.
void add_shipped_quadratic(std::vector<SchemeVariant>& out, const YAML::Node& scene_document,
                           const std::optional<YAML::Node>& quadratic_connections) {
  if (!quadratic_connections) return;
  for (auto& v : out)
    if (same_yaml(v.document["connections"], *quadratic_connections)) {
      v.shipped_quadratic = true;
      return;
    }
  SchemeVariant v;
  v.name = "shipped/quadratic";
  v.family = "shipped";
  v.shipped_quadratic = true;
  v.document = YAML::Clone(scene_document);
  v.document["connections"] = *quadratic_connections;
  out.push_back(v);
}

// The schemes of the connection `cut` that crosses a coupling element (and its reverse
// direction, if the scene lists it): compliant with each reconstruction, interface Jacobian
// with 1, 2 and 10 levels; every other connection as shipped.
void add_cut_variants(std::vector<SchemeVariant>& out, const YAML::Node& scene_document, int cut) {
  const YAML::Node conns = scene_document["connections"];
  int reverse = -1;
  const std::string a = text_of(conns[cut], "from"), b = text_of(conns[cut], "to");
  for (std::size_t i = 0; i < conns.size(); ++i)
    if (text_of(conns[i], "from") == b && text_of(conns[i], "to") == a) reverse = static_cast<int>(i);
  YAML::Node element = YAML::Clone(conns[cut]["coupling"]);
  // The cut rewritten; every other connection as shipped.
  auto with_cut = [&](const std::vector<YAML::Node>& cut_connections) {
    YAML::Node doc = YAML::Clone(scene_document);
    YAML::Node list(YAML::NodeType::Sequence);
    for (std::size_t i = 0; i < conns.size(); ++i) {
      if (static_cast<int>(i) == cut) {
        for (const auto& c : cut_connections) list.push_back(c);
      } else if (static_cast<int>(i) != reverse) {
        list.push_back(YAML::Clone(conns[i]));
      }
    }
    doc["connections"] = list;
    return doc;
  };
  for (const char* rec : {"hold", "linear", "quadratic"}) {
    YAML::Node e = YAML::Clone(element);
    e["scheme"] = to_string(CouplingScheme::compliant);
    e.remove("levels");
    YAML::Node fwd = connection(a, b), back = connection(b, a);
    fwd["order"] = "jacobi";
    fwd["reconstruction"] = rec;
    fwd["coupling"] = e;
    back["order"] = "jacobi";
    back["reconstruction"] = rec;
    SchemeVariant v;
    v.name = to_string(CouplingScheme::compliant) + "/" + rec;
    v.family = to_string(CouplingScheme::compliant);
    v.zero_order_hold_jacobi = std::string(rec) == "hold";
    v.document = with_cut({fwd, back});
    out.push_back(v);
  }
  for (int levels : {1, 2, 10}) {
    YAML::Node e = YAML::Clone(element);
    e["scheme"] = to_string(CouplingScheme::interface_jacobian);
    e["levels"] = levels;
    YAML::Node fwd = connection(a, b);
    fwd["coupling"] = e;
    SchemeVariant v;
    v.name = to_string(CouplingScheme::interface_jacobian) + "/" + std::to_string(levels);
    v.family = to_string(CouplingScheme::interface_jacobian);
    v.document = with_cut({fwd});
    out.push_back(v);
  }
}

// One variant per reconstruction: the connections `first(c, i, n)` picks become
// Gauss-Seidel edges, every other one a Jacobi edge reconstructed with `rec`.
void add_ordered_variants(std::vector<SchemeVariant>& out, const YAML::Node& scene_document, const std::string& family,
                          const std::function<bool(const YAML::Node&, std::size_t, std::size_t)>& first) {
  for (const char* rec : {"hold", "linear", "quadratic"}) {
    YAML::Node doc = YAML::Clone(scene_document);
    std::size_t i = 0;
    const std::size_t n = doc["connections"].size();
    for (auto c : doc["connections"]) {
      const bool gs = first(c, i, n);
      ++i;
      if (gs) {
        c["order"] = "gauss_seidel";
        c.remove("reconstruction");
        c.remove("initial");  // a Gauss-Seidel edge waits for the partner's step-0 sample
      } else {
        c["order"] = "jacobi";
        c["reconstruction"] = rec;
      }
    }
    SchemeVariant v;
    v.name = family + "/" + rec;
    v.family = family;
    v.zero_order_hold_jacobi = family == "jacobi" && std::string(rec) == "hold";
    v.document = doc;
    out.push_back(v);
  }
}

}  // namespace

std::vector<SchemeVariant> scheme_variants(const YAML::Node& scene_document) {
  std::vector<SchemeVariant> out;
  const YAML::Node conns = scene_document["connections"];
  if (!conns || !conns.IsSequence() || conns.size() == 0) return out;
  // The scene as shipped.
  SchemeVariant shipped;
  shipped.name = "shipped";
  shipped.family = "shipped";
  shipped.shipped = true;
  shipped.document = YAML::Clone(scene_document);
  out.push_back(shipped);
  const std::optional<YAML::Node> quadratic_connections = quadratic_connections_of(scene_document);

  // The connection that crosses a coupling element (at most one is handled: the shipped
  // scenes have one).
  int cut = -1;
  for (std::size_t i = 0; i < conns.size(); ++i)
    if (conns[i]["coupling"]) cut = static_cast<int>(i);
  if (cut >= 0) {
    add_cut_variants(out, scene_document, cut);
    add_shipped_quadratic(out, scene_document, quadratic_connections);
    return out;
  }

  // No coupling element: the order and reconstruction of every connection.
  bool has_gs = false;
  for (const auto& c : conns) has_gs = has_gs || text_of(c, "order", "jacobi") == "gauss_seidel";
  add_ordered_variants(out, scene_document, "jacobi", [](const YAML::Node&, std::size_t, std::size_t) { return false; });
  // The scene's Gauss-Seidel edges (or, without any, its first connection) first.
  add_ordered_variants(out, scene_document, "gauss_seidel", [&](const YAML::Node& c, std::size_t i, std::size_t) {
    return has_gs ? text_of(c, "order", "jacobi") == "gauss_seidel" : i == 0;
  });
  // The other ordering: the edges that were Jacobi go first (Gauss-Seidel) and the
  // Gauss-Seidel ones become Jacobi (without any Gauss-Seidel edge: the last connection
  // first). The validator refuses an ordering with a Gauss-Seidel cycle.
  add_ordered_variants(out, scene_document, "gauss_seidel_reversed", [&](const YAML::Node& c, std::size_t i, std::size_t n) {
    return has_gs ? text_of(c, "order", "jacobi") != "gauss_seidel" : i + 1 == n;
  });
  add_shipped_quadratic(out, scene_document, quadratic_connections);
  return out;
}
}  // namespace mechsim::bench
