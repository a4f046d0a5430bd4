#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "csv.h"
#include "json_io.h"
#include "mechsim/config/hash.h"
#include "provenance.h"

namespace mechsim::tools {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<double> numbers_of(const std::string& csv_line) {
  std::vector<double> out;
  std::istringstream fields(csv_line);
  for (std::string field; std::getline(fields, field, ',');) {
    out.push_back(std::strtod(field.c_str(), nullptr));
  }
  return out;
}

// A fresh, empty directory per test (removed at its end when the test passes).
fs::path scratch_dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("mechsim_common_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(JsonIo, WritesPrettyJsonThatReadsBackAndLeavesNoTemporaryFile) {
  const fs::path dir = scratch_dir("json");
  const std::string path = (dir / "result.json").string();
  const nlohmann::json doc = {{"schema_version", schema_version}, {"values", {1.5, -2.0}}};
  write_json_file(path, doc);
  write_json_file(path, doc);  // overwriting is fine
  const std::string text = read_text(path);
  EXPECT_EQ(nlohmann::json::parse(text), doc);
  EXPECT_NE(text.find("\n  \"schema_version\": \"1\""), std::string::npos) << text;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(JsonIo, FailureNamesThePath) {
  const std::string path = "/nonexistent-mechsim-dir/result.json";
  try {
    write_json_file(path, nlohmann::json::object());
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(Csv, HeaderAndRowsReadBackExactly) {
  const fs::path dir = scratch_dir("csv");
  const std::string path = (dir / "signals.csv").string();
  const double third = 1.0 / 3.0;
  const double tiny = std::numeric_limits<double>::denorm_min();
  write_csv(path, {"t", "x, mm", "say \"hi\""}, {{0.0, 0.1}, {third, -1e300}, {tiny, 42.0}});
  std::istringstream lines(read_text(path));
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "t,\"x, mm\",\"say \"\"hi\"\"\"");
  // %.17g round-trips every double exactly, so the comparisons are exact.
  std::getline(lines, line);
  EXPECT_EQ(numbers_of(line), (std::vector<double>{0.0, third, tiny}));
  std::getline(lines, line);
  EXPECT_EQ(numbers_of(line), (std::vector<double>{0.1, -1e300, 42.0}));
  EXPECT_FALSE(std::getline(lines, line));  // exactly two rows
  fs::remove_all(dir);
}

TEST(Csv, ShapeMismatchIsRefused) {
  const std::string path = (scratch_dir("csv_bad") / "bad.csv").string();
  EXPECT_THROW(write_csv(path, {"a", "b"}, {{1.0}}), std::invalid_argument);
  EXPECT_THROW(write_csv(path, {"a", "b"}, {{1.0, 2.0}, {1.0}}), std::invalid_argument);
  EXPECT_FALSE(fs::exists(path));
  fs::remove_all(fs::path(path).parent_path());
}

TEST(Provenance, HashesTheSceneFile) {
  const fs::path dir = scratch_dir("provenance");
  const std::string scene = (dir / "scene.yaml").string();
  const std::string contents = "scene: demo\ntime: {end: 1 s, step: 1 ms}\n";
  std::ofstream(scene, std::ios::binary) << contents;
  const nlohmann::json p = provenance(scene);
  EXPECT_EQ(p.at("scene_file"), scene);
  EXPECT_EQ(p.at("scene_sha256"), config::sha256_hex(contents));
  EXPECT_FALSE(p.at("mechsim_version").get<std::string>().empty());
  EXPECT_FALSE(p.at("git_commit").get<std::string>().empty());
  EXPECT_FALSE(p.at("host").get<std::string>().empty());
  EXPECT_TRUE(std::regex_match(p.at("created_utc").get<std::string>(),
                               std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")))
      << p.at("created_utc");
  ASSERT_TRUE(p.at("dds").is_object());
  for (const auto& [vendor, version] : p.at("dds").items()) {
    EXPECT_TRUE(version.is_string() && !version.get<std::string>().empty()) << vendor;
  }
  fs::remove_all(dir);
}

TEST(Provenance, WithoutSceneAndWithAMissingScene) {
  const nlohmann::json p = provenance("");
  EXPECT_TRUE(p.at("scene_file").is_null());
  EXPECT_TRUE(p.at("scene_sha256").is_null());
  EXPECT_THROW(provenance("/nonexistent-mechsim-dir/scene.yaml"), std::runtime_error);
}

}  // namespace
}  // namespace mechsim::tools
