#include "mechsim/fmi_export/fmu_writer.h"

#include <zip.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <pugixml.hpp>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "exact_decimal.h"

namespace fs = std::filesystem;

namespace mechsim::fmi_export {

namespace {

const char* causality(VariableKind k) {
  switch (k) {
    case VariableKind::input: return "input";
    case VariableKind::output: return "output";
    case VariableKind::parameter: return "parameter";
  }
  return "local";
}

void add_units(pugi::xml_node root, const std::vector<ExportedVariable>& variables) {
  const auto units = unit_definitions(variables);
  if (units.empty()) return;
  auto defs = root.append_child("UnitDefinitions");
  // Base-unit attribute names of FMI 2 and 3, in config::BaseUnit order (m, kg, s, A, rad).
  static const char* const kBase[config::kNumBaseUnits] = {"m", "kg", "s", "A", "rad"};
  for (const auto& u : units) {
    auto unit = defs.append_child("Unit");
    unit.append_attribute("name") = u.name.c_str();
    if (std::isnan(u.factor)) continue;  // a name mechsim's unit parser does not know
    auto base = unit.append_child("BaseUnit");
    for (int i = 0; i < config::kNumBaseUnits; ++i)
      if (u.dimension.exp[i] != 0) base.append_attribute(kBase[i]) = u.dimension.exp[i];
    if (u.factor != 1.0) base.append_attribute("factor") = exact(u.factor).c_str();
  }
}

// The inputs an output depends on directly (the block's feedthrough), as FMI lists them:
// 1-based ScalarVariable indices (FMI 2) or value references (FMI 3).
std::string dependencies(const ExportedParticipant& p, const ExportedVariable& output) {
  std::string deps;
  for (const int input : p.block().outputs()[output.index].feedthrough) {
    // Inputs come first: variable index i has value reference i + 1 and FMI 2 index i + 1.
    const unsigned ref = ExportedParticipant::value_reference(static_cast<std::size_t>(input));
    deps += (deps.empty() ? "" : " ") + std::to_string(ref);
  }
  return deps;
}

}  // namespace

std::string model_identifier(const std::string& participant) {
  std::string id;
  for (const char c : participant) id += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  if (id.empty() || std::isdigit(static_cast<unsigned char>(id[0]))) id = "p_" + id;
  return id;
}

ExportConfig export_config(const config::Scene& scene, const ExportRequest& request) {
  const config::ParticipantSpec* spec = nullptr;
  std::string names;
  for (const auto& p : scene.participants) {
    names += (names.empty() ? "" : ", ") + p.name;
    if (p.name == request.participant) spec = &p;
  }
  if (spec == nullptr)
    throw std::invalid_argument(scene.file + ": participants: expected a participant '" + request.participant +
                                "' (the scene has " + names + ")");
  if (spec->type != request.type)
    throw std::invalid_argument(scene.file + ": " + spec->key_path + ".type: participant '" + spec->name + "' is a " +
                                spec->type + ", not a " + request.type);
  if (spec->fmu)
    throw std::invalid_argument(scene.file + ": " + spec->key_path +
                                ".fmu: the participant is played by an FMU already; export a native participant");
  ExportConfig c;
  c.participant = spec->name;
  c.type = spec->type;
  c.scene = scene.file;
  c.solver = spec->solver;
  c.params = spec->params;
  c.time = scene.time;
  for (const auto& conn : scene.connections)
    if ((conn.from == spec->name || conn.to == spec->name) && conn.coupling) c.coupling = *conn.coupling;
  return c;
}

namespace {

// The passes of model_description_xml, one per element of the document, in document order.

// <fmiModelDescription> and its attributes.
pugi::xml_node add_model_description(pugi::xml_document& doc, const ExportConfig& c, bool v2, const std::string& token) {
  auto decl = doc.append_child(pugi::node_declaration);
  decl.append_attribute("version") = "1.0";
  decl.append_attribute("encoding") = "UTF-8";
  auto root = doc.append_child("fmiModelDescription");
  root.append_attribute("fmiVersion") = v2 ? "2.0" : "3.0";
  root.append_attribute("modelName") = c.participant.c_str();
  root.append_attribute(v2 ? "guid" : "instantiationToken") = token.c_str();
  root.append_attribute("description") =
      ("mechsim participant '" + c.participant + "' (" + c.type + ") of " + fs::path(c.scene).filename().string() +
       ", with its own " + c.solver.method + " integrator (rtol " + exact(c.solver.rtol) + ", atol " +
       exact(c.solver.atol) + ")")
          .c_str();
  root.append_attribute("generationTool") = "mechsim fmu export";
  root.append_attribute("variableNamingConvention") = "flat";
  if (v2) root.append_attribute("numberOfEventIndicators") = 0;
  return root;
}

// <CoSimulation>: the capability flags it really has (docs/fmi.md): any step length (the
// integrator stops where it is asked to), FMU state get/set and serialized
// (ExportedParticipant::State); no derivatives, no early return, no event mode.
void add_co_simulation(pugi::xml_node root, bool v2, const std::string& id) {
  auto cs = root.append_child("CoSimulation");
  cs.append_attribute("modelIdentifier") = id.c_str();
  cs.append_attribute("needsExecutionTool") = "false";
  cs.append_attribute("canHandleVariableCommunicationStepSize") = "true";
  cs.append_attribute("canBeInstantiatedOnlyOncePerProcess") = "false";
  cs.append_attribute("maxOutputDerivativeOrder") = 0;
  if (v2) {
    cs.append_attribute("canInterpolateInputs") = "false";
    cs.append_attribute("canRunAsynchronuously") = "false";
    cs.append_attribute("canNotUseMemoryManagementFunctions") = "true";
    cs.append_attribute("canGetAndSetFMUstate") = "true";
    cs.append_attribute("canSerializeFMUstate") = "true";
    cs.append_attribute("providesDirectionalDerivative") = "false";
  } else {
    cs.append_attribute("canGetAndSetFMUState") = "true";
    cs.append_attribute("canSerializeFMUState") = "true";
    cs.append_attribute("providesDirectionalDerivatives") = "false";
    cs.append_attribute("providesAdjointDerivatives") = "false";
    cs.append_attribute("providesIntermediateUpdate") = "false";
    cs.append_attribute("canReturnEarlyAfterIntermediateUpdate") = "false";
    cs.append_attribute("hasEventMode") = "false";
  }
}

// <DefaultExperiment>, when the scene's time section came along.
void add_default_experiment(pugi::xml_node root, const ExportConfig& c) {
  if (!c.time) return;
  auto experiment = root.append_child("DefaultExperiment");
  experiment.append_attribute("startTime") = exact(c.time->start).c_str();
  experiment.append_attribute("stopTime") = exact(c.time->end).c_str();
  experiment.append_attribute("stepSize") = exact(c.time->step).c_str();
}

// <ModelVariables>: FMI 3's independent time first, then every exported variable.
void add_model_variables(pugi::xml_node root, const ExportedParticipant& p, bool v2) {
  auto vars = root.append_child("ModelVariables");
  if (!v2) {
    auto t = vars.append_child("Float64");
    t.append_attribute("name") = "time";
    t.append_attribute("valueReference") = ExportedParticipant::kTimeValueReference;
    t.append_attribute("causality") = "independent";
    t.append_attribute("variability") = "continuous";
    t.append_attribute("unit") = "s";
  }
  for (std::size_t i = 0; i < p.variables().size(); ++i) {
    const ExportedVariable& v = p.variables()[i];
    pugi::xml_node var = vars.append_child(v2 ? "ScalarVariable" : "Float64");
    var.append_attribute("name") = v.name.c_str();
    var.append_attribute("valueReference") = ExportedParticipant::value_reference(i);
    var.append_attribute("description") = v.description.c_str();
    var.append_attribute("causality") = causality(v.kind);
    var.append_attribute("variability") = v.kind == VariableKind::parameter ? "fixed" : "continuous";
    if (v.kind == VariableKind::output) var.append_attribute("initial") = "calculated";
    if (v.kind == VariableKind::parameter) var.append_attribute("initial") = "exact";
    pugi::xml_node typed = v2 ? var.append_child("Real") : var;
    if (!v.unit.empty()) typed.append_attribute("unit") = v.unit.c_str();
    if (v.kind != VariableKind::output) typed.append_attribute("start") = exact(v.start).c_str();
  }
}

// <ModelStructure>: the outputs with their dependencies, and the initial unknowns.
void add_model_structure(pugi::xml_node root, const ExportedParticipant& p, bool v2) {
  auto structure = root.append_child("ModelStructure");
  pugi::xml_node outputs = v2 ? structure.append_child("Outputs") : structure;
  for (std::size_t i = 0; i < p.variables().size(); ++i) {
    const ExportedVariable& v = p.variables()[i];
    if (v.kind != VariableKind::output) continue;
    auto u = outputs.append_child(v2 ? "Unknown" : "Output");
    // FMI 2 lists ScalarVariable indices (1-based); FMI 3 value references. Both are i + 1.
    u.append_attribute(v2 ? "index" : "valueReference") = ExportedParticipant::value_reference(i);
    u.append_attribute("dependencies") = dependencies(p, v).c_str();
  }
  pugi::xml_node initial = v2 ? structure.append_child("InitialUnknowns") : structure;
  for (std::size_t i = 0; i < p.variables().size(); ++i)
    if (p.variables()[i].kind == VariableKind::output)
      initial.append_child(v2 ? "Unknown" : "InitialUnknown")
          .append_attribute(v2 ? "index" : "valueReference") = ExportedParticipant::value_reference(i);
}

}  // namespace

std::string model_description_xml(const ExportedParticipant& p, int fmi_version, const std::string& id,
                                   const std::string& token) {
  if (fmi_version != 2 && fmi_version != 3) throw std::invalid_argument("expected FMI version 2 or 3");
  const bool v2 = fmi_version == 2;
  pugi::xml_document doc;
  pugi::xml_node root = add_model_description(doc, p.config(), v2, token);
  add_co_simulation(root, v2, id);
  // FMI 3's independent variable `time` (add_model_variables) is in s: defined with the others.
  std::vector<ExportedVariable> with_time = p.variables();
  if (!v2) with_time.push_back({"time", VariableKind::output, 0, "s", 0.0, ""});
  add_units(root, with_time);
  add_default_experiment(root, p.config());
  add_model_variables(root, p, v2);
  add_model_structure(root, p, v2);
  std::ostringstream out;
  doc.save(out, "  ");
  return out.str();
}

namespace {

// One archive being written; every libzip failure names the file.
class ZipWriter {
 public:
  explicit ZipWriter(const std::string& path) : path_(path) {
    int error = 0;
    archive_ = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    if (archive_ == nullptr) {
      zip_error_t e;
      zip_error_init_with_code(&e, error);
      const std::string why = zip_error_strerror(&e);
      zip_error_fini(&e);
      throw std::runtime_error("cannot create " + path + ": " + why);
    }
  }
  ~ZipWriter() {
    if (archive_ != nullptr) zip_discard(archive_);
  }
  // stored: no compression (the binaries: an importer unpacks them at every instantiation,
  // and inflating 3 MB was the largest part of loading the FMU, docs/fmi.md).
  void add(const std::string& name, std::string content, bool stored = false) {
    contents_.push_back(std::move(content));
    const std::string& data = contents_.back();
    zip_source_t* source = zip_source_buffer(archive_, data.data(), data.size(), 0);
    const zip_int64_t index =
        source == nullptr ? -1 : zip_file_add(archive_, name.c_str(), source, ZIP_FL_OVERWRITE | ZIP_FL_ENC_UTF_8);
    if (index < 0) {
      if (source != nullptr) zip_source_free(source);
      fail("cannot add " + name);
    }
    if (stored && zip_set_file_compression(archive_, static_cast<zip_uint64_t>(index), ZIP_CM_STORE, 0) < 0)
      fail("cannot store " + name + " uncompressed");
  }
  void close() {
    if (zip_close(archive_) < 0) fail("cannot write");
    archive_ = nullptr;
  }

 private:
  [[noreturn]] void fail(const std::string& what) {
    throw std::runtime_error(path_ + ": " + what + ": " + zip_strerror(archive_));
  }
  std::string path_;
  zip_t* archive_ = nullptr;
  std::vector<std::string> contents_;  // kept alive until zip_close reads them
};

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path + " (to pack into the FMU)");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

void write_fmu(const ExportConfig& config, const ExportRequest& request) {
  const ExportedParticipant participant(config);  // builds the block: bad params are refused here
  const std::string id = model_identifier(config.participant);
  // A token that changes with what the FMU plays (its configuration), as the standard asks
  // of a guid / instantiationToken.
  const std::string yaml = write_export_config(config);
  char token[64];
  std::snprintf(token, sizeof token, "{mechsim-%016zx}", std::hash<std::string>{}(yaml));
  const std::string binary = read_file(request.binary);
  const std::string platform = std::string("binaries/") + (request.fmi_version == 2 ? "linux64" : "x86_64-linux") + "/";
  ZipWriter zip(request.output);
  zip.add("modelDescription.xml", model_description_xml(participant, request.fmi_version, id, token));
  zip.add(platform + id + ".so", binary, true);
  // The binary finds it beside itself (RUNPATH $ORIGIN): the FMU needs no yaml-cpp installed.
  zip.add(platform + MECHSIM_FMU_BUNDLED_SONAME, read_file(MECHSIM_FMU_BUNDLED_LIBRARY), true);
  zip.add("resources/participant.yaml", yaml);
  zip.close();
}

std::string default_fmu_binary() {
  if (const char* env = std::getenv("MECHSIM_FMU_BINARY"); env != nullptr && *env != '\0') return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return "";
  for (const fs::path& candidate : {exe.parent_path() / "mechsim_fmu.so", exe.parent_path() / "../lib/mechsim/mechsim_fmu.so"})
    if (fs::exists(candidate, ec)) return candidate.lexically_normal().string();
  return "";
}

}  // namespace mechsim::fmi_export
