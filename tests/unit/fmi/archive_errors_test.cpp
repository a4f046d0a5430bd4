// Bad FMU files are refused with a message that names the file (and the participant where
// known) and the cause. The archives without a binary are written here with libzip.
#include <fstream>
#include <functional>

#include <gtest/gtest.h>

#include "fmu_files.h"
#include "mechsim/fmi/archive.h"
#include "mechsim/fmi/instance.h"

namespace mechsim::fmi {
namespace {

using test::ScratchFolder;
using test::test_fmu;
using test::write_zip;

// Runs `f`, expects an FmuError whose message holds every one of `parts`; returns it.
std::string refusal(const std::function<void()>& f, const std::vector<std::string>& parts) {
  try {
    f();
  } catch (const FmuError& e) {
    const std::string what = e.what();
    for (const auto& p : parts) EXPECT_NE(what.find(p), std::string::npos) << "'" << p << "' not in: " << what;
    return what;
  }
  ADD_FAILURE() << "not refused";
  return "";
}

constexpr const char* kMinimalFmi2 = R"(<?xml version="1.0"?>
<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g">
  <CoSimulation modelIdentifier="m"/>
  <ModelVariables/>
</fmiModelDescription>)";

class ArchiveErrors : public ::testing::Test {
 protected:
  ScratchFolder scratch_;
  std::string path(const std::string& name) const { return scratch_.path(name).string(); }
  void open(const std::string& file) { FmuArchive archive(FmuLabel{file, "ctrl"}); }
};

TEST_F(ArchiveErrors, MissingFile) {
  const std::string file = path("absent.fmu");
  refusal([&] { open(file); }, {"FMU '" + file + "' (participant 'ctrl')", "no such file"});
}

TEST_F(ArchiveErrors, TextFileRenamedFmu) {
  const std::string file = path("text.fmu");
  std::ofstream(file) << "this is not an archive\n";
  refusal([&] { open(file); }, {"FMU '" + file + "' (participant 'ctrl')", "is not a zip archive"});
}

TEST_F(ArchiveErrors, ZipWithoutModelDescription) {
  const std::string file = path("empty.fmu");
  write_zip(file, {{"binaries/", ""}, {"documentation/readme.txt", "hello"}});
  refusal([&] { open(file); }, {"FMU '" + file + "'", "no modelDescription.xml at its root"});
}

TEST_F(ArchiveErrors, ModelDescriptionInASubfolderIsNotAtTheRoot) {
  const std::string file = path("nested.fmu");
  write_zip(file, {{"lag/modelDescription.xml", kMinimalFmi2}});
  refusal([&] { open(file); }, {"no modelDescription.xml at its root"});
}

TEST_F(ArchiveErrors, MalformedXmlNamesLineAndColumn) {
  const std::string file = path("malformed.fmu");
  // Line 3 holds the unclosed tag; pugixml reports the mismatch where </fmiModelDescription> is.
  write_zip(file, {{"modelDescription.xml",
                    "<?xml version=\"1.0\"?>\n<fmiModelDescription fmiVersion=\"2.0\">\n  <CoSimulation>\n"
                    "</fmiModelDescription>\n"}});
  const std::string what = refusal([&] { open(file); }, {"FMU '" + file + "'", "not well-formed XML", "line 4"});
  EXPECT_NE(what.find("column"), std::string::npos) << what;
}

TEST_F(ArchiveErrors, NotAModelDescription) {
  const std::string file = path("html.fmu");
  write_zip(file, {{"modelDescription.xml", "<html><body/></html>"}});
  refusal([&] { open(file); }, {"root element is <html>", "expected <fmiModelDescription>"});
}

TEST_F(ArchiveErrors, Fmi1IsRefusedNamingTheSupportedVersions) {
  const std::string file = path("fmi1.fmu");
  write_zip(file, {{"modelDescription.xml",
                    "<fmiModelDescription fmiVersion=\"1.0\" modelName=\"m\" modelIdentifier=\"m\" guid=\"g\">"
                    "<ModelVariables/></fmiModelDescription>"}});
  refusal([&] { open(file); }, {"FMU '" + file + "' (participant 'ctrl')", "FMI 1.0",
                                "not supported", "FMI 2.0 and 3.0"});
}

TEST_F(ArchiveErrors, UnknownVersion) {
  const std::string file = path("fmi4.fmu");
  write_zip(file, {{"modelDescription.xml", "<fmiModelDescription fmiVersion=\"4.0\"/>"}});
  refusal([&] { open(file); }, {"fmiVersion '4.0' is not supported", "FMI 2.0 and 3.0"});
}

TEST_F(ArchiveErrors, VariableWithoutValueReference) {
  const std::string file = path("novr.fmu");
  write_zip(file, {{"modelDescription.xml", R"(<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g">
  <CoSimulation modelIdentifier="m"/>
  <ModelVariables><ScalarVariable name="x"><Real/></ScalarVariable></ModelVariables>
</fmiModelDescription>)"}});
  refusal([&] { open(file); }, {"variable 'x' has no valueReference"});
}

TEST_F(ArchiveErrors, NeitherInterface) {
  const std::string file = path("none.fmu");
  write_zip(file, {{"modelDescription.xml", "<fmiModelDescription fmiVersion=\"3.0\" modelName=\"m\"/>"}});
  refusal([&] { open(file); }, {"neither <CoSimulation> nor <ModelExchange>"});
}

TEST_F(ArchiveErrors, EntryOutsideTheFolder) {
  const std::string file = path("escape.fmu");
  write_zip(file, {{"modelDescription.xml", kMinimalFmi2}, {"../escaped.txt", "x"}});
  refusal([&] { open(file); }, {"'../escaped.txt' would land outside"});
  EXPECT_FALSE(std::filesystem::exists(scratch_.path("escaped.txt")));
}

TEST_F(ArchiveErrors, InterfaceTheFmuDoesNotOffer) {
  const std::string file = test_fmu("lag_fmi2_cs");
  const FmuArchive archive(FmuLabel{file, "ctrl"});
  refusal([&] { FmuInstance::create(archive, InterfaceKind::model_exchange, "ctrl"); },
          {"FMU '" + file + "' (participant 'ctrl')", "does not offer the model-exchange interface",
           "it offers co-simulation"});
}

TEST_F(ArchiveErrors, NoBinaryForThisPlatformListsThosePresent) {
  // The FMI 3 lag with its binary moved to other platforms' folders.
  std::vector<std::pair<std::string, std::string>> entries;
  for (auto [name, content] : test::read_zip(test_fmu("lag_fmi3_cs"))) {
    if (name == "binaries/x86_64-linux/lag.so") {
      entries.emplace_back("binaries/x86_64-windows/lag.dll", content);
      entries.emplace_back("binaries/aarch64-darwin/lag.dylib", content);
    } else if (!name.starts_with("binaries/")) {
      entries.emplace_back(name, content);
    }
  }
  const std::string file = path("windows_only.fmu");
  write_zip(file, entries);
  const FmuArchive archive(FmuLabel{file, "ctrl"});
  EXPECT_EQ(archive.platforms(), (std::vector<std::string>{"aarch64-darwin", "x86_64-windows"}));
  refusal([&] { FmuInstance::create(archive, InterfaceKind::co_simulation, "ctrl"); },
          {"FMU '" + file + "' (participant 'ctrl')", "no binary for this platform",
           "binaries/x86_64-linux/lag.so is missing", "aarch64-darwin, x86_64-windows"});
}

TEST_F(ArchiveErrors, NoBinariesAtAll) {
  const std::string file = path("source_only.fmu");
  write_zip(file, {{"modelDescription.xml", kMinimalFmi2}});
  const FmuArchive archive(FmuLabel{file, ""});
  refusal([&] { archive.binary_path(InterfaceKind::co_simulation); },
          {"FMU '" + file + "':", "binaries/linux64/m.so is missing", "the archive has no binaries/ folder"});
}

TEST_F(ArchiveErrors, BinaryThatDoesNotLoad) {
  const std::string file = path("garbage_binary.fmu");
  write_zip(file, {{"modelDescription.xml", kMinimalFmi2}, {"binaries/linux64/m.so", "not an ELF file"}});
  const FmuArchive archive(FmuLabel{file, "ctrl"});
  refusal([&] { FmuInstance::create(archive, InterfaceKind::co_simulation, "ctrl"); },
          {"FMU '" + file + "' (participant 'ctrl')", "cannot load its binary binaries/linux64/m.so"});
}

// Archive limits (archive.h): 16 MiB of zeros deflate to ~16 kB, a ratio near 1000 : 1, far
// past the default 200 : 1 and any real FMU's; refused from the zip's directory, before a
// byte is unpacked (no folder is made), with the numbers and the key that raises them.
class ArchiveLimitsTest : public ArchiveErrors {
 protected:
  void SetUp() override {
    write_zip(path("zeros.fmu"), {{"modelDescription.xml", kMinimalFmi2}, {"resources/zeros.bin", std::string(16u << 20, '\0')}});
    set_unpack_root(scratch_.path("run/fmu"));
  }
  void TearDown() override { set_unpack_root(""); }
};

TEST_F(ArchiveLimitsTest, ARatioPastTheLimitIsRefusedBeforeUnpacking) {
  const std::string file = path("zeros.fmu");
  refusal([&] { FmuArchive(FmuLabel{file, "ctrl"}); },
          {"FMU '" + file + "' (participant 'ctrl')", "unpacks to 16.00 MiB (16777", "a ratio of",
           "the limits are 2.00 GiB unpacked and a ratio of 200 : 1", "unpack_limits", "refused before unpacking"});
  EXPECT_FALSE(std::filesystem::exists(scratch_.path("run/fmu")));
}

TEST_F(ArchiveLimitsTest, ASizePastTheLimitIsRefusedAndRaisedLimitsAdmitIt) {
  const std::string file = path("zeros.fmu");
  refusal([&] { FmuArchive(FmuLabel{file, "ctrl"}, ArchiveLimits{1u << 20, 1e6}); },
          {"unpacks to 16.00 MiB", "the limits are 1.00 MiB unpacked and a ratio of 1e+06 : 1"});
  const FmuArchive raised(FmuLabel{file, "ctrl"}, ArchiveLimits{32u << 20, 1e6});
  EXPECT_EQ(std::filesystem::file_size(raised.folder() / "resources/zeros.bin"), 16u << 20);
}

// With an unpack root (a run's <run folder>/fmu), an FMU unpacks once: the second archive
// of the same participant (another process of the run, a restart) finds the folder whole
// and reuses it, and neither removes it (the launcher does, at the end of the run).
TEST_F(ArchiveLimitsTest, UnpackedOncePerRunFolderAndLeftForTheLauncher) {
  std::filesystem::path first_folder;
  std::filesystem::file_time_type unpacked_at;
  {
    const FmuArchive first(FmuLabel{test_fmu("lag_fmi2_cs"), "lag"});
    first_folder = first.folder();
    EXPECT_EQ(first_folder, scratch_.path("run/fmu/lag_fmi2_cs-lag"));
    unpacked_at = std::filesystem::last_write_time(first_folder / "modelDescription.xml");
    const FmuArchive second(FmuLabel{test_fmu("lag_fmi2_cs"), "lag"});
    EXPECT_EQ(second.folder(), first_folder);
  }
  ASSERT_TRUE(std::filesystem::exists(first_folder / "modelDescription.xml"));
  EXPECT_EQ(std::filesystem::last_write_time(first_folder / "modelDescription.xml"), unpacked_at) << "unpacked twice";
}

}  // namespace
}  // namespace mechsim::fmi
