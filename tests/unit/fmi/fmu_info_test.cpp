// `mechsim fmu info`: the text and the JSON of a test FMU hold what its description says.
#include <sstream>

#include <gtest/gtest.h>

#include "fmu_files.h"
#include "fmu_info.h"

namespace mechsim::tools {
namespace {

using fmi::test::test_fmu;

TEST(FmuInfo, TextNamesVersionInterfaceFlagsVariablesAndPlatforms) {
  const fmi::FmuArchive archive(fmi::FmuLabel{test_fmu("lag_fmi2_cs"), ""});
  const std::string text = format_fmu_info(archive);
  for (const char* part : {"FMI version      2.0", "model            lag",
                           "co-simulation: model identifier lag, binary binaries/linux64/lag.so",
                           "variable step yes, get/set state no, serialize state no",
                           "platforms        linux64  (this host: linux64)", "continuous states 1, event indicators 0",
                           "variables (6)"})
    EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in:\n" << text;
  // The row of T, column by column: its unit comes from its declared type.
  std::istringstream lines(text);
  std::string line;
  std::vector<std::string> row;
  while (std::getline(lines, line))
    if (line.starts_with("  T ")) {
      std::istringstream words(line);
      for (std::string w; words >> w;) row.push_back(w);
    }
  EXPECT_EQ(row, (std::vector<std::string>{"T", "parameter", "fixed", "Real", "s", "0.1", "4"})) << text;
}

TEST(FmuInfo, JsonForScripts) {
  const fmi::FmuArchive archive(fmi::FmuLabel{test_fmu("faulty_fmi3_me"), ""});
  const nlohmann::json j = fmu_info_json(archive);
  EXPECT_EQ(j["fmi_version"], "3.0");
  EXPECT_EQ(j["platforms"], nlohmann::json::array({"x86_64-linux"}));
  ASSERT_EQ(j["interfaces"].size(), 1u);
  EXPECT_EQ(j["interfaces"][0]["kind"], "model-exchange");
  EXPECT_EQ(j["interfaces"][0]["host_binary"], "binaries/x86_64-linux/faulty.so");
  EXPECT_FALSE(j["interfaces"][0].contains("can_handle_variable_step"));  // co-simulation only
  ASSERT_EQ(j["variables"].size(), 6u);
  const auto& fault = j["variables"][3];
  EXPECT_EQ(fault["name"], "fault");
  EXPECT_EQ(fault["type"], "Int32");
  EXPECT_EQ(fault["causality"], "parameter");
  EXPECT_EQ(fault["start"], "0");
  EXPECT_EQ(j["variables"][1]["unit"], "V.s");
  EXPECT_TRUE(j["variables"][1]["start"].is_null());
}

}  // namespace
}  // namespace mechsim::tools
