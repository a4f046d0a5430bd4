// modelDescription.xml of the test FMUs (FMI 2 and 3, co-simulation and model exchange) and
// of hand-written descriptions for what the test FMUs do not have.
#include <gtest/gtest.h>

#include "fmu_files.h"
#include "mechsim/fmi/archive.h"

namespace mechsim::fmi {
namespace {

using test::test_fmu;

struct LagCase {
  const char* stem;
  FmiVersion version;
  InterfaceKind kind;
};

class LagDescription : public ::testing::TestWithParam<LagCase> {};

TEST_P(LagDescription, VersionInterfaceVariablesAndPlatform) {
  const LagCase c = GetParam();
  const FmuArchive archive(FmuLabel{test_fmu(c.stem), ""});
  const ModelDescription& md = archive.description();
  EXPECT_EQ(md.version, c.version);
  EXPECT_EQ(md.model_name, "lag");
  EXPECT_EQ(md.instantiation_token, c.version == FmiVersion::fmi2 ? "{6c1a9b52-lag-fmi2}" : "{6c1a9b52-lag-fmi3}");
  ASSERT_EQ(md.interfaces.size(), 1u);
  const Interface& i = md.interfaces[0];
  EXPECT_EQ(i.kind, c.kind);
  EXPECT_EQ(i.model_identifier, "lag");
  EXPECT_EQ(i.can_handle_variable_step, c.kind == InterfaceKind::co_simulation);
  EXPECT_FALSE(i.can_get_and_set_state);
  EXPECT_FALSE(i.can_serialize_state);
  EXPECT_FALSE(i.needs_execution_tool);
  EXPECT_EQ(md.number_of_continuous_states, 1);
  EXPECT_EQ(md.number_of_event_indicators, 0);
  // The state is y: der(y) is declared its derivative and listed as the state derivative.
  ASSERT_EQ(md.state_variables.size(), 1u);
  ASSERT_GE(md.state_variables[0], 0);
  EXPECT_EQ(md.variables.at(static_cast<std::size_t>(md.state_variables[0])).name, "y");
  ASSERT_TRUE(md.default_step_size.has_value());
  EXPECT_DOUBLE_EQ(*md.default_step_size, 0.001);

  const Variable* u = md.find_variable("u");
  ASSERT_NE(u, nullptr);
  EXPECT_EQ(u->value_reference, 0u);
  EXPECT_EQ(u->causality, Causality::input);
  EXPECT_EQ(u->variability, Variability::continuous);
  EXPECT_EQ(u->type, ValueType::real);
  EXPECT_EQ(u->type_element, c.version == FmiVersion::fmi2 ? "Real" : "Float64");
  EXPECT_EQ(u->unit, "V");
  EXPECT_EQ(u->start, std::optional<std::string>("0"));
  const Variable* y = md.find_variable("y");
  ASSERT_NE(y, nullptr);
  EXPECT_EQ(y->causality, Causality::output);
  EXPECT_FALSE(y->start.has_value());
  // T has no unit of its own: it comes from its declared type "Time".
  const Variable* t = md.find_variable("T");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->causality, Causality::parameter);
  EXPECT_EQ(t->variability, Variability::fixed);
  EXPECT_EQ(t->declared_type, "Time");
  EXPECT_EQ(t->unit, "s");
  EXPECT_EQ(t->start, std::optional<std::string>("0.1"));
  const Variable* k = md.find_variable("k");
  ASSERT_NE(k, nullptr);
  EXPECT_EQ(k->unit, "");

  const UnitDefinition* volt = md.find_unit("V");
  ASSERT_NE(volt, nullptr);
  EXPECT_EQ(volt->kg, 1);
  EXPECT_EQ(volt->m, 2);
  EXPECT_EQ(volt->s, -3);
  EXPECT_EQ(volt->A, -1);
  EXPECT_DOUBLE_EQ(volt->factor, 1.0);

  const std::string platform = c.version == FmiVersion::fmi2 ? "linux64" : "x86_64-linux";
  EXPECT_EQ(archive.platforms(), std::vector<std::string>{platform});
  EXPECT_EQ(archive.binary_path(c.kind).filename(), "lag.so");
  EXPECT_TRUE(std::filesystem::exists(archive.binary_path(c.kind)));
}

INSTANTIATE_TEST_SUITE_P(TestFmus, LagDescription,
                         ::testing::Values(LagCase{"lag_fmi2_cs", FmiVersion::fmi2, InterfaceKind::co_simulation},
                                           LagCase{"lag_fmi2_me", FmiVersion::fmi2, InterfaceKind::model_exchange},
                                           LagCase{"lag_fmi3_cs", FmiVersion::fmi3, InterfaceKind::co_simulation},
                                           LagCase{"lag_fmi3_me", FmiVersion::fmi3, InterfaceKind::model_exchange}),
                         [](const auto& info) { return std::string(info.param.stem); });

TEST(ModelDescription, IntegerAndBooleanVariablesOfBothVersions) {
  for (const char* stem : {"faulty_fmi2_cs", "faulty_fmi3_cs"}) {
    const FmuArchive archive(FmuLabel{test_fmu(stem), ""});
    const Variable* fault = archive.description().find_variable("fault");
    ASSERT_NE(fault, nullptr) << stem;
    EXPECT_EQ(fault->type, ValueType::integer) << stem;
    EXPECT_EQ(fault->value_reference, 3u) << stem;
    const Variable* faulted = archive.description().find_variable("faulted");
    ASSERT_NE(faulted, nullptr) << stem;
    EXPECT_EQ(faulted->type, ValueType::boolean) << stem;
    EXPECT_EQ(faulted->causality, Causality::output) << stem;
    EXPECT_EQ(faulted->variability, Variability::discrete) << stem;
  }
}

TEST(ModelDescription, TheArchiveFolderIsRemovedWithTheArchive) {
  std::filesystem::path folder;
  {
    const FmuArchive archive(FmuLabel{test_fmu("lag_fmi2_cs"), ""});
    folder = archive.folder();
    EXPECT_TRUE(std::filesystem::exists(folder / "modelDescription.xml"));
  }
  EXPECT_FALSE(std::filesystem::exists(folder));
}

// What the test FMUs lack: FMI 2 String/Enumeration, FMI 3 arrays and other widths, an FMU
// with both interfaces, event indicators, FMI 2 flags by their FMI 2 spelling.
TEST(ModelDescription, TypesMechsimDoesNotExchangeAreListedAsOther) {
  const std::string fmi2 = R"(<?xml version="1.0"?>
<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g" numberOfEventIndicators="2">
  <ModelExchange modelIdentifier="m_me" providesDirectionalDerivative="true"/>
  <CoSimulation modelIdentifier="m_cs" canGetAndSetFMUstate="true" canSerializeFMUstate="true"
                needsExecutionTool="true"/>
  <ModelVariables>
    <ScalarVariable name="s" valueReference="0" causality="parameter" variability="fixed"><String start="x"/></ScalarVariable>
    <ScalarVariable name="e" valueReference="1" causality="output"><Enumeration declaredType="E"/></ScalarVariable>
  </ModelVariables>
</fmiModelDescription>)";
  const ModelDescription md2 = parse_model_description(fmi2, FmuLabel{"m.fmu", ""});
  ASSERT_EQ(md2.interfaces.size(), 2u);
  const Interface* me = md2.find_interface(InterfaceKind::model_exchange);
  const Interface* cs = md2.find_interface(InterfaceKind::co_simulation);
  ASSERT_TRUE(me && cs);
  EXPECT_EQ(me->model_identifier, "m_me");
  EXPECT_TRUE(me->provides_directional_derivatives);
  EXPECT_TRUE(cs->can_get_and_set_state);
  EXPECT_TRUE(cs->can_serialize_state);
  EXPECT_TRUE(cs->needs_execution_tool);
  EXPECT_FALSE(cs->can_handle_variable_step);
  EXPECT_EQ(md2.number_of_event_indicators, 2);
  EXPECT_EQ(md2.variables.at(0).type, ValueType::other);
  EXPECT_EQ(md2.variables.at(0).type_element, "String");
  EXPECT_EQ(md2.variables.at(1).type_element, "Enumeration");
  EXPECT_EQ(md2.variables.at(1).variability, Variability::discrete);

  const std::string fmi3 = R"(<?xml version="1.0"?>
<fmiModelDescription fmiVersion="3.0" modelName="m" instantiationToken="t">
  <CoSimulation modelIdentifier="m" canGetAndSetFMUState="true" providesDirectionalDerivatives="true"/>
  <ModelVariables>
    <Float32 name="f" valueReference="1" causality="output"/>
    <Float64 name="a" valueReference="2" causality="output"><Dimension start="3"/></Float64>
    <Int32 name="n" valueReference="3" causality="structuralParameter" variability="fixed" start="3"/>
  </ModelVariables>
  <ModelStructure><EventIndicator valueReference="1"/></ModelStructure>
</fmiModelDescription>)";
  const ModelDescription md3 = parse_model_description(fmi3, FmuLabel{"m.fmu", ""});
  EXPECT_TRUE(md3.interfaces.at(0).can_get_and_set_state);
  EXPECT_TRUE(md3.interfaces.at(0).provides_directional_derivatives);
  EXPECT_EQ(md3.number_of_event_indicators, 1);
  EXPECT_EQ(md3.variables.at(0).type, ValueType::other);
  EXPECT_EQ(md3.variables.at(0).variability, Variability::continuous);  // Float32 defaults like Float64
  EXPECT_EQ(md3.variables.at(1).type, ValueType::other);
  EXPECT_EQ(md3.variables.at(1).type_element, "Float64[]");
  EXPECT_EQ(md3.variables.at(2).type, ValueType::integer);
  EXPECT_EQ(md3.variables.at(2).causality, Causality::structural_parameter);
}

// <ModelStructure> output dependencies: listed (FMI 2: 1-based indices, FMI 3: value
// references), empty (depends on nothing), absent (may depend on everything), and refused
// where they name no variable.
TEST(ModelDescription, OutputDependencies) {
  const auto fmi2 = [](const std::string& outputs) {
    return R"(<?xml version="1.0"?>
<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g">
  <ModelExchange modelIdentifier="m"/>
  <ModelVariables>
    <ScalarVariable name="u1" valueReference="0" causality="input"><Real start="0"/></ScalarVariable>
    <ScalarVariable name="u2" valueReference="1" causality="input"><Real start="0"/></ScalarVariable>
    <ScalarVariable name="x" valueReference="2"><Real/></ScalarVariable>
    <ScalarVariable name="y1" valueReference="3" causality="output"><Real/></ScalarVariable>
    <ScalarVariable name="y2" valueReference="4" causality="output"><Real/></ScalarVariable>
    <ScalarVariable name="y3" valueReference="5" causality="output"><Real/></ScalarVariable>
  </ModelVariables>
  <ModelStructure><Outputs>)" + outputs + R"(</Outputs></ModelStructure>
</fmiModelDescription>)";
  };
  const ModelDescription md2 = parse_model_description(
      fmi2(R"(<Unknown index="4" dependencies="2 3"/><Unknown index="5" dependencies=""/><Unknown index="6"/>)"),
      FmuLabel{"m.fmu", ""});
  ASSERT_EQ(md2.output_dependencies.size(), 3u);
  EXPECT_EQ(md2.output_dependencies[0].variable, 3);
  EXPECT_EQ(md2.output_dependencies[0].dependencies, (std::vector<int>{1, 2}));  // u2 and x
  EXPECT_EQ(md2.output_dependencies[1].dependencies, std::vector<int>{});
  EXPECT_FALSE(md2.output_dependencies[2].dependencies.has_value());
  EXPECT_EQ(md2.find_output_dependencies(4), &md2.output_dependencies[1]);
  EXPECT_EQ(md2.find_output_dependencies(0), nullptr);
  try {
    parse_model_description(fmi2(R"(<Unknown index="4" dependencies="1 7"/>)"), FmuLabel{"m.fmu", ""});
    ADD_FAILURE() << "not refused";
  } catch (const FmuError& e) {
    EXPECT_NE(std::string(e.what()).find("<ModelStructure><Outputs>: dependency 7 is not a ScalarVariable (1..6)"),
              std::string::npos)
        << e.what();
  }

  const std::string fmi3 = R"(<?xml version="1.0"?>
<fmiModelDescription fmiVersion="3.0" modelName="m" instantiationToken="t">
  <ModelExchange modelIdentifier="m"/>
  <ModelVariables>
    <Float64 name="u1" valueReference="10" causality="input" start="0"/>
    <Float64 name="u2" valueReference="11" causality="input" start="0"/>
    <Float64 name="y1" valueReference="20" causality="output"/>
    <Float64 name="y2" valueReference="21" causality="output"/>
  </ModelVariables>
  <ModelStructure><Output valueReference="20" dependencies="11"/><Output valueReference="21"/></ModelStructure>
</fmiModelDescription>)";
  const ModelDescription md3 = parse_model_description(fmi3, FmuLabel{"m.fmu", ""});
  ASSERT_EQ(md3.output_dependencies.size(), 2u);
  EXPECT_EQ(md3.output_dependencies[0].variable, 2);
  EXPECT_EQ(md3.output_dependencies[0].dependencies, std::vector<int>{1});
  EXPECT_FALSE(md3.output_dependencies[1].dependencies.has_value());
  std::string bad = fmi3;
  bad.replace(bad.find(R"(dependencies="11")"), 17, R"(dependencies="12")");
  try {
    parse_model_description(bad, FmuLabel{"m.fmu", ""});
    ADD_FAILURE() << "not refused";
  } catch (const FmuError& e) {
    EXPECT_NE(std::string(e.what()).find("<ModelStructure><Output>: dependency 12 is no variable's valueReference"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mechsim::fmi
