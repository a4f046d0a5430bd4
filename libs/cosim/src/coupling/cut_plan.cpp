#include "coupling/cut_plan.h"

#include <stdexcept>

#include "mechsim/catalog/coupling/coupling_spec.h"

namespace mechsim::cosim::coupling {

void plan_interface_jacobian_cut(const config::Scene& scene, const config::ConnectionSpec& c, PlannedNode& from,
                                 PlannedNode& to) {
  const auto refuse = [&](const std::string& key_path, const std::string& expected) {
    throw config::ConfigError(scene.file, key_path, expected);
  };
  const std::string where = c.key_path + ".coupling";
  const CouplingSpec spec = parse_coupling(*c.coupling);
  for (const PlannedNode* n : {&from, &to})
    if (!n->type->cut_port)
      refuse(where, "expected both participants of an interface_jacobian coupling to offer a cut port; a " + n->type->name +
                        " has none");
  if (from.type->cut_port->twist_sign == to.type->cut_port->twist_sign)
    refuse(where, "expected one participant the coupling torque loads (a tachometer) and one it drives (a slide)");
  if (c.order != config::EdgeOrder::jacobi)
    refuse(c.key_path + ".order", "expected order: jacobi (the interface_jacobian coupling exchanges one prediction per side and step)");
  for (const auto& other : scene.connections)
    if (other.from == c.to && other.to == c.from)
      refuse(other.key_path, "expected no connection " + c.to + " -> " + c.from + ": the interface_jacobian coupling of " +
                                 c.key_path + " joins them both ways");
  for (PlannedNode* n : {&from, &to}) {
    const CutPort& port = *n->type->cut_port;
    PlannedNode& partner = n == &from ? to : from;
    if (n->cut) refuse(where, "expected at most one interface_jacobian cut per participant ('" + n->name() + "' has two)");
    PlannedCut cut;
    cut.partner = partner.name();
    cut.topic = n->name() + "/coupling";
    cut.partner_topic = partner.name() + "/coupling";
    cut.type = transport::find_topic_type("CouplingPrediction");
    cut.torque_input = n->block->input_index(port.torque_input);
    cut.angle_output = n->block->output_index(port.angle_output);
    cut.speed_output = n->block->output_index(port.speed_output);
    if (cut.torque_input < 0 || cut.angle_output < 0 || cut.speed_output < 0 || !cut.type)
      throw std::logic_error("cut port of node type " + n->type->name + " does not match its block in torque mode");
    for (int o : {cut.angle_output, cut.speed_output})
      if (!n->block->outputs()[o].feedthrough.empty())
        throw std::logic_error("cut port of node type " + n->type->name + ": angle and speed must not depend on inputs directly");
    cut.twist_sign = port.twist_sign;
    cut.levels = spec.levels;
    cut.stiffness = spec.params.stiffness;
    cut.damping = spec.params.damping;
    cut.key_path = where;
    n->cut = std::move(cut);
  }
}


}  // namespace mechsim::cosim::coupling
