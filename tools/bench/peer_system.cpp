#include "peer_system.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/fmi_export/fmu_writer.h"

namespace mechsim::bench {

namespace {

// The peer cannot take the scene: exit code 2 with this message.
struct Refused : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string xml_escaped(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// XML comments may not hold "--".
std::string comment_text(std::string s) {
  for (std::size_t at; (at = s.find("--")) != std::string::npos;) s.replace(at, 2, "- -");
  return xml_escaped(s);
}

std::string short_decimal(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", v);  // 25 us, not the scene's 24.999999999999998 us (libcosim truncates to ns)
  return buf;
}

// The FMU variable of a block port, as the export names it (ExportedParticipant: an input
// may be `<name>_in`), checked against the plan's block (the same node type, same params).
const std::string& port_variable(const fmi_export::ExportedParticipant& exported, const models::Block& planned,
                                 fmi_export::VariableKind kind, int index) {
  const bool input = kind == fmi_export::VariableKind::input;
  const auto i = static_cast<std::size_t>(index);
  const std::string& expected = input ? planned.inputs()[i].name : planned.outputs()[i].name;
  const std::string& got = input ? exported.block().inputs()[i].name : exported.block().outputs()[i].name;
  if (expected != got)
    throw std::logic_error("exported block of '" + exported.config().participant + "' has port '" + got + "' where the plan has '" +
                           expected + "'");
  for (const auto& v : exported.variables())
    if (v.kind == kind && v.index == index) return v.name;
  throw std::logic_error("no exported variable for port '" + expected + "' of '" + exported.config().participant + "'");
}

}  // namespace

int write_peer_system(const std::string& scene_path, const PeerSystemOptions& options, std::ostream& out) {
  try {
    const config::Scene scene = config::load_scene(scene_path, options.set_overrides);
    const cosim::ScenePlan plan = cosim::ScenePlan::build(scene);
    if (plan.grid()->is_adaptive()) throw Refused("adaptive macro step (time.step: adaptive): OSP's fixedStep has one step");
    for (const auto& node : plan.nodes()) {
      if (node.cut)
        throw Refused("interface-Jacobian cut between '" + node.name() + "' and '" + node.cut->partner +
                      "': its torque predictions are no FMI variables, an FMI 2 master cannot exchange them");
      if (node.fmu) throw Refused("participant '" + node.name() + "' is played by an FMU (not exported again)");
    }
    const std::string binary = fmi_export::default_fmu_binary();
    if (binary.empty()) throw std::runtime_error("no FMU binary found (build target mechsim_fmu)");
    std::filesystem::create_directories(options.dir);

    std::vector<std::unique_ptr<fmi_export::ExportedParticipant>> exported;
    std::ostringstream simulators;
    for (const auto& node : plan.nodes()) {
      fmi_export::ExportRequest request;
      request.type = node.spec->type;
      request.participant = node.name();
      request.fmi_version = 2;
      request.output = (std::filesystem::path(options.dir) / (node.name() + ".fmu")).string();
      request.binary = binary;
      const fmi_export::ExportConfig config = fmi_export::export_config(scene, request);
      fmi_export::write_fmu(config, request);
      exported.push_back(std::make_unique<fmi_export::ExportedParticipant>(config));
      simulators << "    <Simulator name=\"" << xml_escaped(node.name()) << "\" source=\"" << xml_escaped(node.name())
                 << ".fmu\"/>\n";
    }

    std::ostringstream connections;
    std::size_t ports = 0, reinterpreted = 0;
    for (std::size_t j = 0; j < plan.nodes().size(); ++j) {
      const auto& reader = plan.nodes()[j];
      for (const auto& edge : reader.inputs) {
        std::size_t s = 0;
        while (plan.nodes()[s].name() != edge.from) ++s;
        const auto& source = plan.nodes()[s];
        if (edge.order != config::EdgeOrder::jacobi || edge.reconstruction != config::Reconstruction::hold) ++reinterpreted;
        for (const auto& [field, input] : edge.field_to_input) {
          const int output = source.published_outputs[static_cast<std::size_t>(field)];
          connections << "    <VariableConnection>\n"
                      << "      <Variable simulator=\"" << xml_escaped(source.name()) << "\" name=\""
                      << xml_escaped(port_variable(*exported[s], *source.block, fmi_export::VariableKind::output, output)) << "\"/>\n"
                      << "      <Variable simulator=\"" << xml_escaped(reader.name()) << "\" name=\""
                      << xml_escaped(port_variable(*exported[j], *reader.block, fmi_export::VariableKind::input, input)) << "\"/>\n"
                      << "    </VariableConnection>\n";
          ++ports;
        }
      }
    }

    const std::string xml_path = (std::filesystem::path(options.dir) / "OspSystemStructure.xml").string();
    std::ofstream xml(xml_path);
    xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        << "<!-- " << comment_text(scene_path) << " for libcosim, written by mechsim bench (peer system) -->\n"
        << "<OspSystemStructure xmlns=\"http://opensimulationplatform.com/MSMI/OSPSystemStructure\" version=\"0.1\">\n"
        << "  <StartTime>" << short_decimal(scene.time.start) << "</StartTime>\n"
        << "  <BaseStepSize>" << short_decimal(scene.time.step) << "</BaseStepSize>\n"
        << "  <Algorithm>fixedStep</Algorithm>\n"
        << "  <Simulators>\n" << simulators.str() << "  </Simulators>\n"
        << "  <Connections>\n" << connections.str() << "  </Connections>\n"
        << "</OspSystemStructure>\n";
    xml.close();
    if (!xml) throw std::runtime_error("cannot write " + xml_path);
    // The scene as the peer couples it, for the floor with the peer's coupling: the
    // --set overrides that make every connection Jacobi and held.
    const std::string sets_path = (std::filesystem::path(options.dir) / "peer-coupling.sets").string();
    std::ofstream sets(sets_path);
    for (const auto& c : scene.connections) {
      if (c.order != config::EdgeOrder::jacobi) sets << c.key_path << ".order=jacobi\n";
      if (c.reconstruction != config::Reconstruction::hold) sets << c.key_path << ".reconstruction=hold\n";
    }
    sets.close();
    if (!sets) throw std::runtime_error("cannot write " + sets_path);
    out << "wrote " << xml_path << ": " << plan.nodes().size() << " FMI 2 co-simulation FMUs, " << ports
        << " port connections, step " << scene.time.step << " s";
    if (reinterpreted > 0)
      out << "; " << reinterpreted << " of the scene's edges are Gauss-Seidel or reconstructed, fixedStep takes every edge Jacobi, held";
    out << "\n";
    return 0;
  } catch (const Refused& e) {
    std::fprintf(stderr, "mechsim bench --peer-system: not for the peer: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim bench --peer-system: %s\n", e.what());
    return 1;
  }
}

}  // namespace mechsim::bench
