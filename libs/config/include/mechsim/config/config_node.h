// Validated access to a YAML document: every value is read through a ConfigNode, which
// knows the file and the key path it came from, so that any refusal names both:
//   scene.yaml: participants.follower.params.mass: expected a mass, e.g. '25 kg', got '25 mm'
//
// Keyed accessors (quantity("mass", dim::mass)) read a child of a map; as_*() read this
// node itself (sequence elements). A key whose value is empty (`mass:` or `mass: ~`) counts
// as missing. Duplicate keys in a map are refused when the document is loaded.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "mechsim/config/units.h"

namespace mechsim::config {

// what() is "<file>: <key.path>: <expected>", or "<file>: <expected>" when the error
// concerns the whole file (unreadable, YAML syntax).
class ConfigError : public std::runtime_error {
 public:
  ConfigError(std::string file, std::string key_path, std::string expected, int line = 0);

  const std::string& file() const { return file_; }
  const std::string& key_path() const { return key_path_; }
  const std::string& expected() const { return expected_; }
  // 1-based line in the file where the offending value (or its parent map) starts; 0 if
  // unknown (values set with set_override have none).
  int line() const { return line_; }

 private:
  std::string file_;
  std::string key_path_;
  std::string expected_;
  int line_;
};

class ConfigNode {
 public:
  // An empty node without a file, so that structs holding a ConfigNode can be filled later.
  ConfigNode() = default;
  // Reads and parses a YAML file; the file label in errors is `path` as given.
  static ConfigNode load_file(const std::string& path);
  static ConfigNode from_string(std::string text, std::string file_label);

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }  // "" for the root
  const YAML::Node& yaml() const { return node_; }
  // The node (with any overrides applied) written back as YAML, e.g. for the run folder.
  std::string to_yaml() const;

  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_scalar() const { return node_.IsScalar(); }
  // Number of entries of a map or sequence, 0 for a scalar.
  std::size_t size() const;

  // --- maps ---------------------------------------------------------------------------
  // True when the key is present with a non-empty value.
  bool has(std::string_view key) const;
  ConfigNode child(std::string_view key) const;  // missing -> "missing key"
  std::optional<ConfigNode> optional_child(std::string_view key) const;
  std::vector<std::string> keys() const;  // in document order
  // Refuses any key not listed: "unknown key 'masss'; allowed: mass, stiffness".
  void allow_only(std::initializer_list<std::string_view> allowed) const;
  void allow_only(const std::vector<std::string>& allowed) const;

  // --- sequences ----------------------------------------------------------------------
  ConfigNode at(std::size_t index) const;  // key path "law[2]"

  // --- this node's own scalar value ---------------------------------------------------
  std::string as_string() const;
  double as_quantity(Dimension expected) const;  // bare number = SI
  double as_number() const;                      // dimensionless; "30 %" gives 0.3
  long as_integer() const;
  bool as_boolean() const;  // true/false (also yes/no, on/off)
  std::string as_choice(const std::vector<std::string>& allowed) const;

  // --- a child's scalar value (required unless *_or) ----------------------------------
  double quantity(std::string_view key, Dimension expected) const;
  double quantity_or(std::string_view key, Dimension expected, double default_si) const;
  double positive_quantity(std::string_view key, Dimension expected) const;      // > 0
  double non_negative_quantity(std::string_view key, Dimension expected) const;  // >= 0
  double positive_quantity_or(std::string_view key, Dimension expected, double default_si) const;
  double non_negative_quantity_or(std::string_view key, Dimension expected,
                                  double default_si) const;
  double number(std::string_view key) const;
  double number_or(std::string_view key, double default_value) const;
  long integer(std::string_view key) const;
  long integer_or(std::string_view key, long default_value) const;
  bool boolean(std::string_view key) const;
  bool boolean_or(std::string_view key, bool default_value) const;
  std::string string(std::string_view key) const;
  std::string string_or(std::string_view key, std::string default_value) const;
  // One of `allowed`; the error lists them.
  std::string choice(std::string_view key, const std::vector<std::string>& allowed) const;
  std::string choice_or(std::string_view key, const std::vector<std::string>& allowed,
                        std::string default_value) const;

  // Throws ConfigError for this node: "<file>: <path>: <expected>".
  [[noreturn]] void fail(std::string expected) const;

  // Creates or replaces the scalar at `dotted_path` (relative to this node), as for
  // `--set participants.cam.params.speed=60 rpm`. Missing maps on the way are created;
  // a segment may index an existing sequence ("connections[0].scheme"). Going through a
  // scalar, or replacing a map or sequence by a scalar, is a ConfigError.
  void set_override(const std::string& dotted_path, const std::string& value);

 private:
  ConfigNode(std::string file, std::string path, YAML::Node node);

  std::string child_path(std::string_view key) const;
  void require_map() const;
  // The value under `key`, or nullopt when absent or empty; requires a map.
  std::optional<YAML::Node> find(std::string_view key) const;
  int line() const;
  std::string describe_value() const;  // "'25 mm'", "a map", "nothing", ... for messages

  std::string file_;
  std::string path_;
  YAML::Node node_;
};

}  // namespace mechsim::config
