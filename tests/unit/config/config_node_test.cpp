#include "mechsim/config/config_node.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

namespace mechsim::config {
namespace {

constexpr char kScene[] = R"(scene: demo
time: {end: 2 s, step: 1 ms}
participants:
  follower:
    type: follower
    params:
      mass: 25 mm
      good_mass: 2.5 kg
      zero_mass: 0 kg
      negative_damping: -1 N s/m
      zero_damping: 0 N s/m
      empty:
      count: 3
      fraction: 2.5
      flag: yes
      list: [1, 2]
  cam:
    type: cam_shaft
    params:
      speed: 30 rpm
law:
  - {kind: cycloid}
  - {kind: harmonic}
  - {kind: polynomial}
)";

ConfigNode scene() { return ConfigNode::from_string(kScene, "scene.yaml"); }

ConfigNode follower_params() {
  return scene().child("participants").child("follower").child("params");
}

// Runs `f` and returns the ConfigError it throws (fails the test if it does not).
template <class F>
ConfigError error_of(F&& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e;
  }
  ADD_FAILURE() << "no ConfigError thrown";
  return ConfigError("", "", "");
}

TEST(ConfigNode, MessageNamesFileKeyPathAndExpectation) {
  const ConfigError e = error_of([] { follower_params().quantity("mass", dim::mass); });
  EXPECT_STREQ(e.what(),
               "scene.yaml: participants.follower.params.mass: expected a mass, e.g. '25 kg', "
               "got '25 mm'");
  EXPECT_EQ(e.file(), "scene.yaml");
  EXPECT_EQ(e.key_path(), "participants.follower.params.mass");
  EXPECT_EQ(e.expected(), "expected a mass, e.g. '25 kg', got '25 mm'");
  EXPECT_EQ(e.line(), 7);
}

TEST(ConfigNode, ReadsValidValues) {
  const ConfigNode p = follower_params();
  EXPECT_EQ(p.quantity("good_mass", dim::mass), 2.5);
  EXPECT_EQ(p.integer("count"), 3);
  EXPECT_EQ(p.number("fraction"), 2.5);
  EXPECT_TRUE(p.boolean("flag"));
  const ConfigNode root = scene();
  EXPECT_EQ(root.string("scene"), "demo");
  // 30 rpm = pi rad/s; one multiplication by 2*pi/60, so within a few ulp.
  EXPECT_NEAR(root.child("participants")
                  .child("cam")
                  .child("params")
                  .quantity("speed", dim::angular_velocity),
              std::numbers::pi, 1e-15);
  EXPECT_EQ(root.child("time").positive_quantity("step", dim::time), 1e-3);
}

TEST(ConfigNode, MissingKey) {
  EXPECT_STREQ(error_of([] { follower_params().quantity("stiffness", dim::stiffness); }).what(),
               "scene.yaml: participants.follower.params.stiffness: missing key (expected a "
               "stiffness, e.g. '9 N/mm')");
  EXPECT_STREQ(error_of([] { scene().child("record"); }).what(), "scene.yaml: record: missing key");
  EXPECT_FALSE(scene().has("record"));
  EXPECT_FALSE(scene().optional_child("record").has_value());
}

TEST(ConfigNode, EmptyValueCountsAsMissing) {
  const ConfigNode p = follower_params();
  EXPECT_FALSE(p.has("empty"));
  EXPECT_EQ(p.quantity_or("empty", dim::length, 0.5), 0.5);
  EXPECT_EQ(error_of([&] { p.quantity("empty", dim::length); }).key_path(),
            "participants.follower.params.empty");
}

TEST(ConfigNode, UnknownKey) {
  const ConfigNode p =
      ConfigNode::from_string("params: {masss: 2 kg, stiffness: 9 N/mm}", "a.yaml").child("params");
  const ConfigError e = error_of([&] { p.allow_only({"mass", "stiffness"}); });
  EXPECT_STREQ(e.what(),
               "a.yaml: params.masss: unknown key 'masss'; allowed: mass, stiffness (did you "
               "mean 'mass'?)");
  EXPECT_NO_THROW(p.allow_only({"masss", "stiffness", "other"}));
  // No suggestion when nothing is close.
  EXPECT_STREQ(error_of([&] {
                 p.allow_only({"stiffness", "length"});
               }).what(),
               "a.yaml: params.masss: unknown key 'masss'; allowed: stiffness, length");
}

TEST(ConfigNode, WrongType) {
  const ConfigNode p = follower_params();
  EXPECT_EQ(error_of([&] { p.string("list"); }).expected(), "expected a text value, got a list");
  EXPECT_EQ(error_of([&] { p.quantity("list", dim::length); }).expected(),
            "expected a length, e.g. '25 mm', got a list");
  EXPECT_EQ(error_of([&] { p.integer("fraction"); }).expected(), "expected an integer, got '2.5'");
  EXPECT_EQ(error_of([&] { p.integer("mass"); }).expected(), "expected an integer, got '25 mm'");
  EXPECT_EQ(error_of([&] { p.boolean("count"); }).expected(), "expected true or false, got '3'");
  EXPECT_EQ(error_of([&] { p.child("count").child("x"); }).expected(),
            "expected a map of keys, got '3'");
  EXPECT_EQ(error_of([&] { p.child("count").at(0); }).expected(), "expected a list, got '3'");
  EXPECT_EQ(error_of([&] { p.number("good_mass"); }).key_path(),
            "participants.follower.params.good_mass");
}

TEST(ConfigNode, NonPhysicalValues) {
  const ConfigNode p = follower_params();
  EXPECT_EQ(error_of([&] { p.positive_quantity("zero_mass", dim::mass); }).expected(),
            "expected a value > 0, got '0 kg'");
  EXPECT_EQ(error_of([&] {
              p.non_negative_quantity("negative_damping", dim::viscous_damping);
            }).expected(),
            "expected a value >= 0, got '-1 N s/m'");
  EXPECT_EQ(p.non_negative_quantity("zero_damping", dim::viscous_damping), 0.0);
  EXPECT_EQ(p.positive_quantity_or("absent", dim::mass, 1.0), 1.0);
  EXPECT_THROW(p.positive_quantity_or("zero_mass", dim::mass, 1.0), ConfigError);
  EXPECT_THROW(p.non_negative_quantity_or("negative_damping", dim::viscous_damping, 0.0),
               ConfigError);
}

TEST(ConfigNode, Choice) {
  const ConfigNode root = ConfigNode::from_string("mode: fast", "s.yaml");
  EXPECT_STREQ(error_of([&] {
                 root.choice("mode", {"lockstep", "realtime"});
               }).what(),
               "s.yaml: mode: expected one of 'lockstep', 'realtime', got 'fast'");
  EXPECT_EQ(root.choice("mode", {"slow", "fast"}), "fast");
  EXPECT_EQ(root.choice_or("other", {"a", "b"}, "b"), "b");
  EXPECT_THROW(root.choice_or("mode", {"a", "b"}, "b"), ConfigError);
}

TEST(ConfigNode, DefaultsApplyOnlyWhenAbsent) {
  const ConfigNode p = follower_params();
  EXPECT_EQ(p.string_or("absent", "x"), "x");
  EXPECT_EQ(p.integer_or("absent", 7), 7);
  EXPECT_EQ(p.integer_or("count", 7), 3);
  EXPECT_FALSE(p.boolean_or("absent", false));
  EXPECT_EQ(p.number_or("absent", 0.25), 0.25);
  // A present value is still validated.
  EXPECT_THROW(p.quantity_or("mass", dim::mass, 1.0), ConfigError);
  EXPECT_THROW(p.integer_or("fraction", 1), ConfigError);
}

TEST(ConfigNode, ScalarFormats) {
  const ConfigNode n = ConfigNode::from_string(
      "a: +3\nb: -2\nc: 3.0\nd: 0x10\ne: no\nf: 'true'\ng: 30 %\nh: \"25 mm\"", "f.yaml");
  EXPECT_EQ(n.integer("a"), 3);
  EXPECT_EQ(n.integer("b"), -2);
  EXPECT_THROW(n.integer("c"), ConfigError);
  EXPECT_THROW(n.integer("d"), ConfigError);
  EXPECT_FALSE(n.boolean("e"));
  EXPECT_TRUE(n.boolean("f"));
  EXPECT_EQ(n.number("g"), 0.3);
  EXPECT_EQ(n.quantity("h", dim::length), 0.025);
}

TEST(ConfigNode, Sequences) {
  const ConfigNode law = scene().child("law");
  ASSERT_TRUE(law.is_sequence());
  EXPECT_EQ(law.size(), 3u);
  EXPECT_EQ(law.at(2).path(), "law[2]");
  EXPECT_EQ(law.at(2).string("kind"), "polynomial");
  EXPECT_STREQ(error_of([&] { law.at(1).string("shape"); }).what(),
               "scene.yaml: law[1].shape: missing key");
  EXPECT_EQ(error_of([&] { law.at(3); }).expected(), "index out of range (the list has 3 entries)");
  const ConfigNode list = follower_params().child("list");
  EXPECT_EQ(list.at(1).as_integer(), 2);
  EXPECT_EQ(list.at(1).path(), "participants.follower.params.list[1]");
}

TEST(ConfigNode, KeysInDocumentOrder) {
  EXPECT_EQ(scene().child("participants").keys(), (std::vector<std::string>{"follower", "cam"}));
  EXPECT_EQ(scene().size(), 4u);
}

TEST(ConfigNode, YamlSyntaxError) {
  const ConfigError e = error_of([] { ConfigNode::from_string("a: [1, 2\nb: 3\n", "bad.yaml"); });
  EXPECT_EQ(e.file(), "bad.yaml");
  EXPECT_EQ(e.key_path(), "");
  EXPECT_EQ(std::string(e.what()).rfind("bad.yaml: YAML syntax error at line ", 0), 0u) << e.what();
  EXPECT_GT(e.line(), 0);
}

TEST(ConfigNode, DuplicateKeysAreRefused) {
  const ConfigError e =
      error_of([] { ConfigNode::from_string("a:\n  x: 1\n  y: 2\n  x: 3\n", "dup.yaml"); });
  EXPECT_STREQ(e.what(), "dup.yaml: a.x: duplicate key (first given at line 2)");
  EXPECT_EQ(e.line(), 4);
}

TEST(ConfigNode, LoadFile) {
  const std::string missing = ::testing::TempDir() + "/no_such_scene.yaml";
  const ConfigError e = error_of([&] { ConfigNode::load_file(missing); });
  EXPECT_EQ(e.file(), missing);
  EXPECT_NE(std::string(e.what()).find("cannot read the file"), std::string::npos);

  const std::string path = ::testing::TempDir() + "/config_node_test_scene.yaml";
  {
    std::ofstream out(path);
    out << kScene;
  }
  const ConfigNode root = ConfigNode::load_file(path);
  EXPECT_EQ(root.file(), path);
  EXPECT_EQ(
      error_of([&] {
        root.child("participants").child("follower").child("params").quantity("mass", dim::mass);
      }).file(),
      path);
  std::remove(path.c_str());
}

TEST(ConfigNode, OverrideReplacesAScalar) {
  ConfigNode root = scene();
  root.set_override("participants.cam.params.speed", "60 rpm");
  // 60 rpm = 2 pi rad/s, a single multiplication: a few ulp.
  EXPECT_NEAR(root.child("participants")
                  .child("cam")
                  .child("params")
                  .quantity("speed", dim::angular_velocity),
              2 * std::numbers::pi, 1e-15);
  EXPECT_NE(root.to_yaml().find("speed: 60 rpm"), std::string::npos) << root.to_yaml();
}

TEST(ConfigNode, OverrideCreatesMissingMaps) {
  ConfigNode root = scene();
  root.set_override("participants.cam.solver.rtol", "1e-8");
  EXPECT_EQ(root.child("participants").child("cam").child("solver").number("rtol"), 1e-8);
  root.set_override("time.start", "1 s");
  EXPECT_EQ(root.child("time").quantity("start", dim::time), 1.0);
  EXPECT_EQ(root.child("time").quantity("end", dim::time), 2.0);  // siblings kept
  ConfigNode empty = ConfigNode::from_string("", "empty.yaml");
  empty.set_override("a.b", "x");
  EXPECT_EQ(empty.child("a").string("b"), "x");
  // A misspelt key set from the command line is caught like one in the file.
  root.set_override("participants.cam.params.sped", "1 rpm");
  EXPECT_EQ(error_of([&] {
              root.child("participants").child("cam").child("params").allow_only({"speed"});
            }).key_path(),
            "participants.cam.params.sped");
}

TEST(ConfigNode, OverrideIntoSequences) {
  ConfigNode root = scene();
  root.set_override("law[1].kind", "cycloid");
  EXPECT_EQ(root.child("law").at(1).string("kind"), "cycloid");
  EXPECT_EQ(root.child("law").size(), 3u);
  EXPECT_THROW(root.set_override("law[3].kind", "x"), ConfigError);
  EXPECT_THROW(root.set_override("participants[0].type", "x"), ConfigError);
}

TEST(ConfigNode, OverrideRefusals) {
  ConfigNode root = scene();
  const ConfigError through_scalar =
      error_of([&] { root.set_override("participants.cam.params.speed.value", "1"); });
  EXPECT_STREQ(through_scalar.what(),
               "scene.yaml: participants.cam.params.speed.value: cannot set this value: "
               "'participants.cam.params.speed' is a value, not a map");
  EXPECT_THROW(root.set_override("participants.cam", "5"), ConfigError);  // a map
  EXPECT_THROW(root.set_override("law", "5"), ConfigError);               // a list
  EXPECT_THROW(root.set_override("law.kind", "5"), ConfigError);          // key into a list
  EXPECT_THROW(root.set_override("a..b", "5"), ConfigError);
  EXPECT_THROW(root.set_override("", "5"), ConfigError);
  EXPECT_THROW(root.set_override("law[x].kind", "5"), ConfigError);
  EXPECT_THROW(root.set_override("law[1", "5"), ConfigError);
  // Nothing was changed by the refused overrides.
  EXPECT_EQ(root.child("participants").child("cam").string("type"), "cam_shaft");
  EXPECT_TRUE(root.child("law").is_sequence());
}

TEST(ConfigNode, FailNamesThisNode) {
  const ConfigNode p = follower_params();
  EXPECT_STREQ(error_of([&] { p.child("count").fail("expected at most 2"); }).what(),
               "scene.yaml: participants.follower.params.count: expected at most 2");
}

}  // namespace
}  // namespace mechsim::config
