#pragma once
// Strict YAML configuration (docs/design.md, Conventions: Config). A component's parameters are a
// `struct ...Params` with documented defaults; its loader asks a ConfigReader for each key it
// knows. A key the file lacks keeps the struct's default; a key nobody asked for, a value of the
// wrong type or out of range is a ConfigError naming the file, the key and the valid range.
//
//   ConfigReader config = ConfigReader::from_file("config/camera.yaml");
//   ConfigReader panorama = config.section("panorama");
//   panorama.read("width_px", params.width_px, 8, 16384);
//   config.require_all_known();  // after every loader ran: unknown keys are errors

#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace YAML {
class Node;
}

namespace omninav {

class ConfigReader {
 public:
  static ConfigReader from_file(const std::filesystem::path& file);
  static ConfigReader from_string(const std::string& yaml, const std::string& name);

  // The sub-map at `key` (an empty section when the file lacks it).
  ConfigReader section(const std::string& key) const;

  // Each read leaves `value` untouched when the key is absent.
  // Without a range: the type is checked here, the range by the Params struct's check()
  // (param_check.hpp).
  void read(const std::string& key, double& value) const;
  void read(const std::string& key, int& value) const;
  void read_deg(const std::string& key, double& value_rad) const;
  void read(const std::string& key, double& value, double min, double max) const;
  void read(const std::string& key, int& value, int min, int max) const;
  void read(const std::string& key, bool& value) const;
  void read(const std::string& key, std::string& value,
            const std::vector<std::string>& allowed) const;
  // An angle given in degrees in the file, stored in radians.
  void read_deg(const std::string& key, double& value_rad, double min_deg, double max_deg) const;
  // A number that may be absent or null (`~`): the caller then decides, e.g. "detect it".
  void read(const std::string& key, std::optional<double>& value, double min, double max) const;
  void read(const std::string& key, std::optional<double>& value) const;
  // A non-empty list of numbers, each in [min, max] (`seeds: [1, 2]`).
  void read(const std::string& key, std::vector<double>& values, double min, double max) const;
  void read(const std::string& key, std::vector<int>& values, int min, int max) const;
  // A list of maps, each read like a section; their keys are named "key[i].name" (none when
  // the file lacks the key). Throws ConfigError for anything but a list of maps.
  std::vector<ConfigReader> sections(const std::string& key) const;

  bool has(const std::string& key) const;

  // Throws ConfigError for the first key of the whole file that no reader asked for.
  void require_all_known() const;

  const std::string& source_name() const;

  // Throws ConfigError naming the file and the key, for checks only the caller can make.
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

 private:
  struct Shared;
  ConfigReader(std::shared_ptr<Shared> shared, std::shared_ptr<const YAML::Node> node,
               std::string prefix);
  std::optional<YAML::Node> lookup(const std::string& key) const;
  std::string full_key(const std::string& key) const;
  // `node` (the value of `key`) as a number in [min, max].
  double number(const YAML::Node& node, const std::string& key, double min, double max) const;
  int whole_number(const YAML::Node& node, const std::string& key, int min, int max) const;
  // The items of the list at `key`: none when absent, else a non-empty sequence.
  std::vector<YAML::Node> list(const std::string& key, const std::string& expected) const;

  std::shared_ptr<Shared> shared_;
  std::shared_ptr<const YAML::Node> node_;
  std::string prefix_;
};

}  // namespace omninav
