#include "mechsim/config/config_node.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

namespace mechsim::config {
namespace {

std::string compose_message(const std::string& file, const std::string& key_path,
                            const std::string& expected) {
  return key_path.empty() ? file + ": " + expected : file + ": " + key_path + ": " + expected;
}

std::string quoted_list(const std::vector<std::string>& values) {
  std::string out;
  for (const std::string& v : values) out += (out.empty() ? "'" : ", '") + v + "'";
  return out;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitution});
    }
  }
  return row[b.size()];
}

int line_of(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.line >= 0 ? mark.line + 1 : 0;
}

bool is_empty_value(const YAML::Node& node) { return !node.IsDefined() || node.IsNull(); }

// Refuses duplicate and non-scalar map keys anywhere in the document (yaml-cpp keeps
// duplicates silently and lookups would see only the first).
void check_keys(const std::string& file, const std::string& path, const YAML::Node& node) {
  if (node.IsMap()) {
    std::map<std::string, int> first_line;
    for (const auto& entry : node) {
      const std::string key_path = path.empty() ? "" : path + ".";
      if (!entry.first.IsScalar()) {
        throw ConfigError(file, path, "expected plain keys, got a map or list used as a key",
                          line_of(entry.first));
      }
      const std::string& key = entry.first.Scalar();
      const auto [it, inserted] = first_line.emplace(key, line_of(entry.first));
      if (!inserted) {
        throw ConfigError(file, key_path + key,
                          "duplicate key (first given at line " + std::to_string(it->second) + ")",
                          line_of(entry.first));
      }
      check_keys(file, key_path + key, entry.second);
    }
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      check_keys(file, path + "[" + std::to_string(i) + "]", node[i]);
    }
  }
}

// One step of an override path: a map key or a sequence index.
struct PathStep {
  std::string key;  // empty for an index step
  std::size_t index = 0;
};

}  // namespace

ConfigError::ConfigError(std::string file, std::string key_path, std::string expected, int line)
    : std::runtime_error(compose_message(file, key_path, expected)),
      file_(std::move(file)),
      key_path_(std::move(key_path)),
      expected_(std::move(expected)),
      line_(line) {}

ConfigNode::ConfigNode(std::string file, std::string path, YAML::Node node)
    : file_(std::move(file)), path_(std::move(path)), node_(std::move(node)) {}

ConfigNode ConfigNode::load_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw ConfigError(path, "", std::string("cannot read the file: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ConfigError(path, "", "cannot read the file");
  return from_string(text.str(), path);
}

ConfigNode ConfigNode::from_string(std::string text, std::string file_label) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    const int line = e.mark.line >= 0 ? e.mark.line + 1 : 0;
    std::string where;
    if (line > 0) {
      where = " at line " + std::to_string(line) + ", column " + std::to_string(e.mark.column + 1);
    }
    throw ConfigError(file_label, "", "YAML syntax error" + where + ": " + e.msg, line);
  }
  // An empty document loads as a node without storage; give it some so that
  // set_override on the root can fill it.
  if (root.IsNull()) root.reset(YAML::Node(YAML::NodeType::Null));
  check_keys(file_label, "", root);
  return ConfigNode(std::move(file_label), "", root);
}

std::size_t ConfigNode::size() const {
  return (node_.IsMap() || node_.IsSequence()) ? node_.size() : 0;
}

std::string ConfigNode::child_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

std::string ConfigNode::to_yaml() const {
  YAML::Emitter out;
  out << node_;
  return std::string(out.c_str()) + "\n";
}

int ConfigNode::line() const { return line_of(node_); }

std::string ConfigNode::describe_value() const {
  if (is_empty_value(node_)) return "nothing";
  if (node_.IsMap()) return "a map";
  if (node_.IsSequence()) return "a list";
  return "'" + node_.Scalar() + "'";
}

void ConfigNode::fail(std::string expected) const {
  throw ConfigError(file_, path_, std::move(expected), line());
}

void ConfigNode::require_map() const {
  if (!node_.IsMap()) fail("expected a map of keys, got " + describe_value());
}

std::optional<YAML::Node> ConfigNode::find(std::string_view key) const {
  require_map();
  for (const auto& entry : node_) {
    if (entry.first.Scalar() == key) {
      if (is_empty_value(entry.second)) return std::nullopt;
      return entry.second;
    }
  }
  return std::nullopt;
}

bool ConfigNode::has(std::string_view key) const { return node_.IsMap() && find(key).has_value(); }

ConfigNode ConfigNode::child(std::string_view key) const {
  std::optional<ConfigNode> c = optional_child(key);
  if (!c) throw ConfigError(file_, child_path(key), "missing key", line());
  return *c;
}

std::optional<ConfigNode> ConfigNode::optional_child(std::string_view key) const {
  std::optional<YAML::Node> value = find(key);
  if (!value) return std::nullopt;
  return ConfigNode(file_, child_path(key), *value);
}

std::vector<std::string> ConfigNode::keys() const {
  require_map();
  std::vector<std::string> out;
  for (const auto& entry : node_) out.push_back(entry.first.Scalar());
  return out;
}

void ConfigNode::allow_only(std::initializer_list<std::string_view> allowed) const {
  allow_only(std::vector<std::string>(allowed.begin(), allowed.end()));
}

void ConfigNode::allow_only(const std::vector<std::string>& allowed) const {
  require_map();
  for (const auto& entry : node_) {
    const std::string& key = entry.first.Scalar();
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string message = "unknown key '" + key + "'; allowed: ";
    std::string suggestion;
    std::size_t best = 3;  // suggest only close spellings (up to two edits)
    for (std::size_t i = 0; i < allowed.size(); ++i) {
      message += (i ? ", " : "") + allowed[i];
      const std::size_t d = edit_distance(key, allowed[i]);
      if (d < best) {
        best = d;
        suggestion = allowed[i];
      }
    }
    if (allowed.empty()) message += "none";
    if (!suggestion.empty()) message += " (did you mean '" + suggestion + "'?)";
    throw ConfigError(file_, child_path(key), message, line_of(entry.first));
  }
}

ConfigNode ConfigNode::at(std::size_t index) const {
  if (!node_.IsSequence()) fail("expected a list, got " + describe_value());
  const std::string element_path = path_ + "[" + std::to_string(index) + "]";
  if (index >= node_.size()) {
    throw ConfigError(
        file_, element_path,
        "index out of range (the list has " + std::to_string(node_.size()) + " entries)", line());
  }
  return ConfigNode(file_, element_path, node_[index]);
}

// --- this node's value -----------------------------------------------------------------

std::string ConfigNode::as_string() const {
  if (!node_.IsScalar()) fail("expected a text value, got " + describe_value());
  return node_.Scalar();
}

double ConfigNode::as_quantity(Dimension expected) const {
  if (!node_.IsScalar()) fail("expected " + describe(expected) + ", got " + describe_value());
  try {
    return parse_quantity_as(node_.Scalar(), expected);
  } catch (const UnitError& e) {
    fail(e.what());
  }
}

double ConfigNode::as_number() const { return as_quantity(dim::dimensionless); }

long ConfigNode::as_integer() const {
  if (!node_.IsScalar()) fail("expected an integer, got " + describe_value());
  const std::string& text = node_.Scalar();
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;
  long value = 0;
  const auto [end, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || end != last) fail("expected an integer, got " + describe_value());
  return value;
}

bool ConfigNode::as_boolean() const {
  bool value = false;
  if (!node_.IsScalar() || !YAML::convert<bool>::decode(node_, value)) {
    fail("expected true or false, got " + describe_value());
  }
  return value;
}

std::string ConfigNode::as_choice(const std::vector<std::string>& allowed) const {
  const std::string expected = "expected one of " + quoted_list(allowed);
  if (!node_.IsScalar()) fail(expected + ", got " + describe_value());
  const std::string& value = node_.Scalar();
  if (std::find(allowed.begin(), allowed.end(), value) == allowed.end()) {
    fail(expected + ", got " + describe_value());
  }
  return value;
}

// --- a child's value ---------------------------------------------------------------------

double ConfigNode::quantity(std::string_view key, Dimension expected) const {
  std::optional<ConfigNode> c = optional_child(key);
  if (!c) {
    throw ConfigError(file_, child_path(key), "missing key (expected " + describe(expected) + ")",
                      line());
  }
  return c->as_quantity(expected);
}

double ConfigNode::quantity_or(std::string_view key, Dimension expected, double default_si) const {
  std::optional<ConfigNode> c = optional_child(key);
  return c ? c->as_quantity(expected) : default_si;
}

double ConfigNode::positive_quantity(std::string_view key, Dimension expected) const {
  const double value = quantity(key, expected);
  if (!(value > 0.0)) child(key).fail("expected a value > 0, got " + child(key).describe_value());
  return value;
}

double ConfigNode::non_negative_quantity(std::string_view key, Dimension expected) const {
  const double value = quantity(key, expected);
  if (!(value >= 0.0)) {
    child(key).fail("expected a value >= 0, got " + child(key).describe_value());
  }
  return value;
}

double ConfigNode::positive_quantity_or(std::string_view key, Dimension expected,
                                        double default_si) const {
  return has(key) ? positive_quantity(key, expected) : default_si;
}

double ConfigNode::non_negative_quantity_or(std::string_view key, Dimension expected,
                                            double default_si) const {
  return has(key) ? non_negative_quantity(key, expected) : default_si;
}

double ConfigNode::number(std::string_view key) const { return quantity(key, dim::dimensionless); }

double ConfigNode::number_or(std::string_view key, double default_value) const {
  return quantity_or(key, dim::dimensionless, default_value);
}

long ConfigNode::integer(std::string_view key) const { return child(key).as_integer(); }

long ConfigNode::integer_or(std::string_view key, long default_value) const {
  std::optional<ConfigNode> c = optional_child(key);
  return c ? c->as_integer() : default_value;
}

bool ConfigNode::boolean(std::string_view key) const { return child(key).as_boolean(); }

bool ConfigNode::boolean_or(std::string_view key, bool default_value) const {
  std::optional<ConfigNode> c = optional_child(key);
  return c ? c->as_boolean() : default_value;
}

std::string ConfigNode::string(std::string_view key) const { return child(key).as_string(); }

std::string ConfigNode::string_or(std::string_view key, std::string default_value) const {
  std::optional<ConfigNode> c = optional_child(key);
  return c ? c->as_string() : default_value;
}

std::string ConfigNode::choice(std::string_view key,
                               const std::vector<std::string>& allowed) const {
  std::optional<ConfigNode> c = optional_child(key);
  if (!c) {
    throw ConfigError(file_, child_path(key),
                      "missing key (expected one of " + quoted_list(allowed) + ")", line());
  }
  return c->as_choice(allowed);
}

std::string ConfigNode::choice_or(std::string_view key, const std::vector<std::string>& allowed,
                                  std::string default_value) const {
  std::optional<ConfigNode> c = optional_child(key);
  return c ? c->as_choice(allowed) : default_value;
}

// --- overrides -------------------------------------------------------------------------

void ConfigNode::set_override(const std::string& dotted_path, const std::string& value) {
  const std::string full_path = child_path(dotted_path);
  auto refuse = [&](const std::string& why) {
    throw ConfigError(file_, full_path, "cannot set this value: " + why);
  };

  // "a.b[2].c" -> key a, key b, index 2, key c.
  std::vector<PathStep> steps;
  std::size_t pos = 0;
  while (pos <= dotted_path.size()) {
    std::size_t dot = dotted_path.find('.', pos);
    if (dot == std::string::npos) dot = dotted_path.size();
    std::string_view segment(dotted_path.data() + pos, dot - pos);
    const std::size_t bracket = segment.find('[');
    const std::string_view key = segment.substr(0, bracket);
    if (key.empty()) refuse("the path has an empty key");
    steps.push_back({std::string(key), 0});
    for (std::size_t b = bracket; b != std::string_view::npos;) {
      const std::size_t close = segment.find(']', b);
      std::size_t index = 0;
      const char* first = segment.data() + b + 1;
      const char* last = close == std::string_view::npos ? first : segment.data() + close;
      const auto [end, ec] = std::from_chars(first, last, index);
      if (close == std::string_view::npos || ec != std::errc() || end != last) {
        refuse("'" + std::string(segment) + "' is not of the form key or key[index]");
      }
      steps.push_back({"", index});
      b = close + 1 == segment.size() ? std::string_view::npos : close + 1;
      if (b != std::string_view::npos && segment[b] != '[') {
        refuse("'" + std::string(segment) + "' is not of the form key or key[index]");
      }
    }
    pos = dot + 1;
  }

  // Walk with rebinding handles: `cur = x` would overwrite the node, `cur.reset(x)` moves.
  YAML::Node cur;
  cur.reset(node_);
  std::string walked = path_;
  for (const PathStep& step : steps) {
    if (step.key.empty()) {
      if (!cur.IsSequence()) refuse("'" + walked + "' is not a list");
      if (step.index >= cur.size()) {
        refuse("'" + walked + "' has only " + std::to_string(cur.size()) + " entries");
      }
      walked += "[" + std::to_string(step.index) + "]";
      YAML::Node next = cur[step.index];
      cur.reset(next);
    } else {
      if (cur.IsDefined() && !cur.IsNull() && !cur.IsMap()) {
        refuse("'" + walked + "' is " + (cur.IsSequence() ? "a list" : "a value") + ", not a map");
      }
      walked = walked.empty() ? step.key : walked + "." + step.key;
      YAML::Node next = cur[step.key];  // created (as a map entry) when missing
      cur.reset(next);
    }
  }
  if (cur.IsMap() || cur.IsSequence()) {
    refuse(std::string("it is ") + (cur.IsMap() ? "a map" : "a list") +
           ", and only single values can be set");
  }
  cur = value;
}

}  // namespace mechsim::config
