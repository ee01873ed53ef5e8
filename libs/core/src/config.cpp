#include "omninav/core/config.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "omninav/core/angles.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"

namespace omninav {

struct ConfigReader::Shared {
  std::string name;             // the file, as the user named it
  std::set<std::string> known;  // full dotted keys some loader asked for
  YAML::Node root;
};

namespace {

// Walks every key of `node`, calling `visit` with its dotted path; the maps of a list are named
// by their index ("worlds[2].seeds"). Every key is text: the parse refused any other (KeyChecker).
template <typename Visit>
void for_each_key(const YAML::Node& node, const std::string& prefix, Visit&& visit) {
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      for_each_key(node[i], prefix + "[" + std::to_string(i) + "]", visit);
  }
  if (!node.IsMap()) return;
  for (const auto& entry : node) {
    const std::string key =
        prefix.empty() ? entry.first.Scalar() : prefix + "." + entry.first.Scalar();
    visit(key, entry.second);
    for_each_key(entry.second, key, visit);
  }
}

// yaml-cpp keeps both values of a key written twice in a map (and lookups find the first),
// so a configuration's second value would be dropped without a word. This pass over the
// parser's events, before the document is built, refuses repeated keys, keys that are not
// plain text, and aliases (a configuration needs none, and a few nested aliases make a
// document whose keys number in the billions).
class KeyChecker : public YAML::EventHandler {
 public:
  explicit KeyChecker(std::string name) : name_(std::move(name)) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { node(mark, nullptr); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override {
    fail(mark, "aliases (*name) are not supported in configuration files");
  }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                const std::string& value) override {
    node(mark, &value);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    node(mark, nullptr);
    levels_.emplace_back();
  }
  void OnSequenceEnd() override { levels_.pop_back(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    node(mark, nullptr);
    levels_.emplace_back().is_map = true;
  }
  void OnMapEnd() override { levels_.pop_back(); }

 private:
  struct Level {
    bool is_map = false;
    bool expects_key = true;
    std::map<std::string, int> key_lines;  // 1-based
  };

  // A node starts: in a map, alternately a key (`text` when it is a scalar) and its value.
  void node(const YAML::Mark& mark, const std::string* text) {
    if (levels_.empty() || !levels_.back().is_map) return;
    Level& map = levels_.back();
    map.expects_key = !map.expects_key;
    if (map.expects_key) return;  // that was a value
    if (text == nullptr) fail(mark, "a key must be a name, not a list or a map");
    const auto [found, inserted] = map.key_lines.emplace(*text, mark.line + 1);
    if (!inserted) {
      fail(mark, "key '" + *text + "' appears twice in the same map (first on line " +
                     std::to_string(found->second) + ")");
    }
  }

  [[noreturn]] void fail(const YAML::Mark& mark, const std::string& problem) const {
    throw ConfigError(name_ + ":" + std::to_string(mark.line + 1) + ": " + problem);
  }

  std::string name_;
  std::vector<Level> levels_;
};

}  // namespace

ConfigReader::ConfigReader(std::shared_ptr<Shared> shared, std::shared_ptr<const YAML::Node> node,
                           std::string prefix)
    : shared_(std::move(shared)), node_(std::move(node)), prefix_(std::move(prefix)) {}

ConfigReader ConfigReader::from_string(const std::string& yaml, const std::string& name) {
  auto shared = std::make_shared<Shared>();
  shared->name = name;
  try {
    std::istringstream stream(yaml);
    YAML::Parser parser(stream);
    KeyChecker checker(name);
    parser.HandleNextDocument(checker);
    shared->root = YAML::Load(yaml);
  } catch (const YAML::Exception& error) {
    throw ConfigError(name + ":" + std::to_string(error.mark.line + 1) +
                      ": not valid YAML: " + error.msg);
  }
  if (!shared->root.IsMap() && !shared->root.IsNull()) {
    throw ConfigError(name + ": expected a map of keys at the top level");
  }
  auto node = std::make_shared<const YAML::Node>(shared->root);
  return ConfigReader(std::move(shared), std::move(node), "");
}

ConfigReader ConfigReader::from_file(const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) {
    throw ConfigError(file.string() + ": " + unreadable_file_reason(file, "configuration file"));
  }
  std::ifstream stream(file, std::ios::binary);
  std::stringstream text;
  text << stream.rdbuf();
  if (!stream) throw ConfigError(file.string() + ": cannot read the configuration file");
  return from_string(text.str(), file.string());
}

const std::string& ConfigReader::source_name() const {
  return shared_->name;
}

std::string ConfigReader::full_key(const std::string& key) const {
  return prefix_.empty() ? key : prefix_ + "." + key;
}

void ConfigReader::fail(const std::string& key, const std::string& problem) const {
  throw ConfigError(shared_->name + ": key '" + full_key(key) + "' " + problem);
}

std::optional<YAML::Node> ConfigReader::lookup(const std::string& key) const {
  shared_->known.insert(full_key(key));
  if (!node_->IsMap()) return std::nullopt;
  const YAML::Node value = (*node_)[key];
  if (!value.IsDefined()) return std::nullopt;
  return value;
}

bool ConfigReader::has(const std::string& key) const {
  return node_->IsMap() && (*node_)[key].IsDefined();
}

ConfigReader ConfigReader::section(const std::string& key) const {
  const std::optional<YAML::Node> value = lookup(key);
  if (value && !value->IsMap() && !value->IsNull()) fail(key, "must be a map of keys");
  auto node = std::make_shared<const YAML::Node>(value ? *value : YAML::Node(YAML::NodeType::Map));
  return ConfigReader(shared_, std::move(node), full_key(key));
}

double ConfigReader::number(const YAML::Node& node, const std::string& key, double min,
                            double max) const {
  double parsed = 0.0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, parsed) || !std::isfinite(parsed)) {
    // A read without a range (the Params struct's check() has it) says no range.
    const bool bounded =
        min > std::numeric_limits<double>::lowest() || max < std::numeric_limits<double>::max();
    fail(key, bounded ? "must be a number in [" + general(min) + ", " + general(max) + "]"
                      : "must be a number");
  }
  if (parsed < min || parsed > max) {
    fail(key,
         "= " + general(parsed) + " is out of range [" + general(min) + ", " + general(max) + "]");
  }
  return parsed;
}

int ConfigReader::whole_number(const YAML::Node& node, const std::string& key, int min,
                               int max) const {
  int parsed = 0;
  if (!node.IsScalar() || !YAML::convert<int>::decode(node, parsed)) {
    const bool bounded =
        min > std::numeric_limits<int>::min() || max < std::numeric_limits<int>::max();
    fail(key, bounded ? "must be a whole number in [" + std::to_string(min) + ", " +
                            std::to_string(max) + "]"
                      : "must be a whole number");
  }
  if (parsed < min || parsed > max) {
    fail(key, "= " + std::to_string(parsed) + " is out of range [" + std::to_string(min) + ", " +
                  std::to_string(max) + "]");
  }
  return parsed;
}

void ConfigReader::read(const std::string& key, double& value) const {
  if (const std::optional<YAML::Node> node = lookup(key)) {
    value = number(*node, key, std::numeric_limits<double>::lowest(),
                   std::numeric_limits<double>::max());
  }
}

void ConfigReader::read(const std::string& key, int& value) const {
  if (const std::optional<YAML::Node> node = lookup(key)) {
    value =
        whole_number(*node, key, std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
  }
}

void ConfigReader::read_deg(const std::string& key, double& value_rad) const {
  const std::optional<YAML::Node> node = lookup(key);
  if (!node) return;
  double degrees = 0.0;
  read(key, degrees);
  value_rad = deg_to_rad(degrees);
}

void ConfigReader::read(const std::string& key, double& value, double min, double max) const {
  if (const std::optional<YAML::Node> node = lookup(key)) value = number(*node, key, min, max);
}

void ConfigReader::read(const std::string& key, std::optional<double>& value, double min,
                        double max) const {
  const std::optional<YAML::Node> node = lookup(key);
  if (!node) return;
  if (node->IsNull()) {
    value.reset();
    return;
  }
  double parsed = value.value_or(min);
  read(key, parsed, min, max);
  value = parsed;
}

void ConfigReader::read(const std::string& key, std::optional<double>& value) const {
  read(key, value, std::numeric_limits<double>::lowest(), std::numeric_limits<double>::max());
}

void ConfigReader::read(const std::string& key, int& value, int min, int max) const {
  if (const std::optional<YAML::Node> node = lookup(key))
    value = whole_number(*node, key, min, max);
}

std::vector<YAML::Node> ConfigReader::list(const std::string& key,
                                           const std::string& expected) const {
  const std::optional<YAML::Node> node = lookup(key);
  if (!node) return {};
  if (!node->IsSequence() || node->size() == 0)
    fail(key, "must be a non-empty list of " + expected);
  return {node->begin(), node->end()};
}

void ConfigReader::read(const std::string& key, std::vector<double>& values, double min,
                        double max) const {
  const std::vector<YAML::Node> items = list(key, "numbers");
  if (items.empty()) return;
  values.clear();
  for (std::size_t i = 0; i < items.size(); ++i)
    values.push_back(number(items[i], key + "[" + std::to_string(i) + "]", min, max));
}

void ConfigReader::read(const std::string& key, std::vector<int>& values, int min, int max) const {
  const std::vector<YAML::Node> items = list(key, "whole numbers");
  if (items.empty()) return;
  values.clear();
  for (std::size_t i = 0; i < items.size(); ++i)
    values.push_back(whole_number(items[i], key + "[" + std::to_string(i) + "]", min, max));
}

std::vector<ConfigReader> ConfigReader::sections(const std::string& key) const {
  std::vector<ConfigReader> readers;
  const std::vector<YAML::Node> items = list(key, "maps");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string item_key = key + "[" + std::to_string(i) + "]";
    if (!items[i].IsMap()) fail(item_key, "must be a map of keys");
    readers.push_back(
        ConfigReader(shared_, std::make_shared<const YAML::Node>(items[i]), full_key(item_key)));
  }
  return readers;
}

void ConfigReader::read(const std::string& key, bool& value) const {
  const std::optional<YAML::Node> node = lookup(key);
  if (!node) return;
  bool parsed = false;
  if (!node->IsScalar() || !YAML::convert<bool>::decode(*node, parsed)) {
    fail(key, "must be true or false");
  }
  value = parsed;
}

void ConfigReader::read(const std::string& key, std::string& value,
                        const std::vector<std::string>& allowed) const {
  const std::optional<YAML::Node> node = lookup(key);
  if (!node) return;
  std::string choices;
  for (const std::string& choice : allowed) choices += (choices.empty() ? "" : ", ") + choice;
  if (!node->IsScalar()) fail(key, "must be one of: " + choices);
  const std::string parsed = node->Scalar();
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), parsed) == allowed.end()) {
    fail(key, "= '" + parsed + "' is not one of: " + choices);
  }
  value = parsed;
}

void ConfigReader::read_deg(const std::string& key, double& value_rad, double min_deg,
                            double max_deg) const {
  if (!has(key)) {
    lookup(key);  // still a known key
    return;
  }
  double degrees = rad_to_deg(value_rad);
  read(key, degrees, min_deg, max_deg);
  value_rad = deg_to_rad(degrees);
}

void ConfigReader::require_all_known() const {
  for_each_key(shared_->root, "", [&](const std::string& key, const YAML::Node&) {
    if (!shared_->known.contains(key)) {
      std::string siblings;
      const std::string parent =
          key.substr(0, key.find_last_of('.') == std::string::npos ? 0 : key.find_last_of('.') + 1);
      for (const std::string& known : shared_->known) {
        if (known.rfind(parent, 0) == 0 && known.find('.', parent.size()) == std::string::npos) {
          siblings += (siblings.empty() ? "" : ", ") + known.substr(parent.size());
        }
      }
      throw ConfigError(shared_->name + ": unknown key '" + key + "'" +
                        (siblings.empty() ? "" : " (known here: " + siblings + ")"));
    }
  });
}

}  // namespace omninav
