// What another importer needs of every export (issue 38 item 1; FMPy refused the FMI 3
// exports): each of the six node types exported as FMI 2 and FMI 3
//  - exports every function of the standard's header from its binary (FMI 3.0.2 §2.2: all
//    of fmi3Functions.h, also of interfaces it does not offer; FMI 2: all but model
//    exchange's), checked with dlsym against the lists of fmi2/fmi3_function_names.txt,
//    taken from the standard's headers;
//  - defines in <UnitDefinitions> every unit its model description uses (FMI 3's `time`
//    included).
#include <dlfcn.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mechsim/config/scene.h"
#include "mechsim/fmi/archive.h"
#include "mechsim/fmi_export/fmu_writer.h"

namespace mechsim::fmi_export {
namespace {

namespace fs = std::filesystem;

struct Export {
  const char* type;
  const char* participant;
  const char* scene;
};
struct Case {
  Export e;
  int fmi;
};

// The function names of the standard's header (comments '#'; "name me": model exchange only).
std::vector<std::string> standard_functions(int fmi) {
  std::ifstream in(std::string(MECHSIM_SOURCE_DIR) + "/tests/unit/fmi_export/fmi" + std::to_string(fmi) + "_function_names.txt");
  std::vector<std::string> names;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line.front() == '#') continue;
    std::istringstream words(line);
    std::string name, only;
    words >> name >> only;
    if (only != "me") names.push_back(name);  // the exports are co-simulation FMUs
  }
  return names;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class ExportConformance : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "mechsim-export-conformance-XXXXXX").string();
    folder_ = mkdtemp(pattern.data());
    const Case c = GetParam();
    const config::Scene scene = config::load_scene(std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/" + c.e.scene);
    file_ = (folder_ / "exported.fmu").string();
    const ExportRequest request{c.e.type, c.e.participant, c.fmi, file_, MECHSIM_FMU_BINARY};
    write_fmu(export_config(scene, request), request);
    archive_ = std::make_unique<fmi::FmuArchive>(fmi::FmuLabel{file_, c.e.participant});
  }
  void TearDown() override {
    archive_.reset();
    fs::remove_all(folder_);
  }
  fs::path folder_;
  std::string file_;
  std::unique_ptr<fmi::FmuArchive> archive_;
};

TEST_P(ExportConformance, TheBinaryExportsEveryFunctionOfTheStandardsHeader) {
  const auto names = standard_functions(GetParam().fmi);
  ASSERT_GT(names.size(), GetParam().fmi == 3 ? 70u : 30u) << "the list of the standard's functions is not read";
  void* library = dlopen(archive_->binary_path(fmi::InterfaceKind::co_simulation).c_str(), RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(library, nullptr) << dlerror();
  for (const auto& name : names) EXPECT_NE(dlsym(library, name.c_str()), nullptr) << "the binary lacks " << name;
  dlclose(library);
}

TEST_P(ExportConformance, TheModelDescriptionDefinesEveryUnitItUses) {
  const std::string xml = slurp(archive_->folder() / "modelDescription.xml");
  std::set<std::string> defined, used;
  const std::regex definition(R"re(<Unit name="([^"]*)")re"), use(R"re(\s(?:unit|displayUnit)="([^"]*)")re");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), definition); it != std::sregex_iterator(); ++it) defined.insert((*it)[1]);
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), use); it != std::sregex_iterator(); ++it) used.insert((*it)[1]);
  ASSERT_FALSE(used.empty()) << xml;
  for (const auto& unit : used) EXPECT_TRUE(defined.count(unit)) << "unit '" << unit << "' is used, not defined, in:\n" << xml;
}

constexpr Export kExports[] = {{"cam_shaft", "cam", "cam_press.yaml"},        {"follower", "follower", "cam_lift_off.yaml"},
                               {"servo_amplifier", "servo", "nc_slide_loop.yaml"}, {"tachometer", "tacho", "nc_slide_loop.yaml"},
                               {"slide", "slide", "nc_slide_loop.yaml"},     {"cvt", "cvt", "line_shaft_4.yaml"}};

std::vector<Case> every_case() {
  std::vector<Case> cases;
  for (const Export& e : kExports)
    for (int fmi : {2, 3}) cases.push_back({e, fmi});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(SixTypes, ExportConformance, ::testing::ValuesIn(every_case()), [](const auto& info) {
  return std::string(info.param.e.type) + "_fmi" + std::to_string(info.param.fmi);
});

}  // namespace
}  // namespace mechsim::fmi_export
