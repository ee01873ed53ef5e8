#include "omninav/evaluation/suite.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>

#include "omninav/core/errors.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::evaluation {
namespace {

// A strict reader of one YAML map: every key must be asked for (done() reports the others).
class StrictMap {
 public:
  StrictMap(const YAML::Node& node, std::string where, std::string file)
      : node_(node), where_(std::move(where)), file_(std::move(file)) {
    if (node_ && !node_.IsNull() && !node_.IsMap()) fail("", "expected a map");
  }

  bool has(const std::string& key) {
    known_.insert(key);
    return node_ && node_.IsMap() && node_[key];
  }
  YAML::Node node(const std::string& key) {
    known_.insert(key);
    return node_ && node_.IsMap() ? node_[key] : YAML::Node();
  }

  void read(const std::string& key, double& value, double min, double max) {
    if (!has(key)) return;
    value = scalar<double>(key);
    if (!std::isfinite(value) || value < min || value > max) out_of_range(key, min, max);
  }
  void read(const std::string& key, int& value, int min, int max) {
    if (!has(key)) return;
    value = scalar<int>(key);
    if (value < min || value > max) out_of_range(key, min, max);
  }
  void read(const std::string& key, std::string& value) {
    if (has(key)) value = scalar<std::string>(key);
  }
  template <typename T>
  std::vector<T> list(const std::string& key, T min, T max) {
    const YAML::Node items = node(key);
    if (!items) return {};
    if (!items.IsSequence() || items.size() == 0) fail(key, "expected a non-empty list");
    std::vector<T> values;
    for (const YAML::Node& item : items) {
      try {
        values.push_back(item.as<T>());
      } catch (const YAML::Exception&) {
        fail(key, "'" + item.as<std::string>("?") + "' is not a number");
      }
      if (values.back() < min || values.back() > max) out_of_range(key, min, max);
    }
    return values;
  }

  void done() const {
    if (!node_ || !node_.IsMap()) return;
    for (const auto& entry : node_) {
      const std::string key = entry.first.as<std::string>();
      if (!known_.count(key)) {
        std::string valid;
        for (const std::string& k : known_) valid += (valid.empty() ? "" : ", ") + k;
        fail(key, "unknown key (valid: " + valid + ")");
      }
    }
  }

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw ConfigError(file_ + ": " + where_ +
                      (key.empty() ? "" : (where_.empty() ? "" : ".") + key) + ": " + problem);
  }

 private:
  template <typename T>
  T scalar(const std::string& key) {
    const YAML::Node value = node_[key];
    if (!value.IsScalar()) fail(key, "expected a single value");
    try {
      return value.as<T>();
    } catch (const YAML::Exception&) {
      fail(key, "'" + value.as<std::string>() + "' has the wrong type");
    }
  }
  template <typename T>
  [[noreturn]] void out_of_range(const std::string& key, T min, T max) const {
    std::ostringstream range;
    range << "out of range (" << min << ".." << max << ")";
    fail(key, range.str());
  }

  YAML::Node node_;
  std::string where_;
  std::string file_;
  std::set<std::string> known_;
};

std::string with_key(const std::string& spec, const std::string& key, const std::string& value) {
  return spec + (spec.find(':') == std::string::npos ? ":" : ",") + key + "=" + value;
}

// A camera height as a row label: whole centimetres ("h10cm").
std::string height_label(double height_m) {
  return "-h" + std::to_string(static_cast<long>(std::lround(height_m * 100.0))) + "cm";
}

}  // namespace

std::string family_of(const std::string& spec) {
  return sim::is_obj_path(spec) ? "obj" : sim::WorldSpec(spec).family();
}

Suite parse_suite(const std::string& yaml, const std::string& name,
                  const std::filesystem::path& base_dir) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& error) {
    throw ConfigError(name + ": not valid YAML: " + error.what());
  }
  Suite suite;
  suite.file = name;
  StrictMap top(root, "", name);
  top.read("name", suite.name);
  SuiteParams& p = suite.params;
  {
    StrictMap panorama(top.node("panorama"), "panorama", name);
    panorama.read("width_px", p.width_px, 8, 16384);
    panorama.read("height_px", p.height_px, 1, 4096);
    panorama.done();
  }
  {
    StrictMap compass(top.node("compass"), "compass", name);
    compass.read("fps", p.fps, 0.1, 1000.0);
    compass.read("rotate_turns", p.rotate_turns, 0.1, 100.0);
    compass.read("rotate_rate_deg_s", p.rotate_rate_deg_s, 0.1, 3600.0);
    compass.read("circle_radius_m", p.circle_radius_m, 0.01, 100.0);
    compass.read("speed_m_s", p.speed_m_s, 0.001, 100.0);
    compass.read("wander_length_m", p.wander_length_m, 0.1, 10000.0);
    compass.read("tilt_noise_deg", p.tilt_noise_deg, 0.0, 45.0);
    compass.done();
  }
  {
    StrictMap memory(top.node("memory"), "memory", name);
    memory.read("grid_nx", p.grid_nx, 2, 1000);
    memory.read("grid_ny", p.grid_ny, 2, 1000);
    memory.read("spacing_m", p.spacing_m, 0.001, 100.0);
    memory.read("queries", p.queries, 1, 1000000);
    memory.done();
  }
  {
    StrictMap navigation(top.node("navigation"), "navigation", name);
    navigation.read("trials", p.trials, 1, 1000000);
    navigation.done();
  }
  const YAML::Node worlds = top.node("worlds");
  if (!worlds || !worlds.IsSequence() || worlds.size() == 0) {
    top.fail("worlds", "expected a non-empty list of worlds");
  }
  std::set<std::string> labels;
  for (std::size_t i = 0; i < worlds.size(); ++i) {
    const std::string where = "worlds[" + std::to_string(i) + "]";
    StrictMap entry(worlds[i], where, name);
    std::string label, spec;
    entry.read("name", label);
    entry.read("world", spec);
    if (spec.empty()) entry.fail("world", "required: the --world spec");
    if (label.empty()) label = family_of(spec);
    if (family_of(spec) == "obj" && !base_dir.empty() &&
        std::filesystem::path(spec).is_relative()) {
      spec = (base_dir / spec).lexically_normal().string();
    }
    double spacing_m = p.spacing_m;
    entry.read("spacing_m", spacing_m, 0.001, 100.0);
    int grid_nx = p.grid_nx, grid_ny = p.grid_ny;
    entry.read("grid_nx", grid_nx, 2, 1000);
    entry.read("grid_ny", grid_ny, 2, 1000);
    double obj_scale_to_m = 0.0;
    entry.read("obj_scale_to_m", obj_scale_to_m, 1e-6, 1e6);
    std::vector<int> seeds = entry.list<int>("seeds", 0, 1'000'000'000);
    std::vector<double> heights = entry.list<double>("camera_heights_m", 0.001, 100.0);
    entry.done();
    const bool seeded = !seeds.empty();
    if (seeds.empty()) seeds = {1};
    if (heights.empty()) heights = {1.0};
    for (const int seed : seeds) {
      for (const double height : heights) {
        SuiteWorld world;
        world.family = family_of(spec);
        world.spec = seeded ? with_key(spec, "seed", std::to_string(seed)) : spec;
        world.camera_height_m = height;
        world.spacing_m = spacing_m;
        world.grid_nx = grid_nx;
        world.grid_ny = grid_ny;
        world.obj_scale_to_m = obj_scale_to_m;
        world.seed = static_cast<std::uint32_t>(seed);
        world.label = label + (seeds.size() > 1 ? "-s" + std::to_string(seed) : "") +
                      (heights.size() > 1 ? height_label(height) : "");
        if (!labels.insert(world.label).second) {
          entry.fail("name", "two rows named '" + world.label + "': give the worlds names");
        }
        suite.worlds.push_back(world);
      }
    }
  }
  top.done();
  if (suite.name.empty()) suite.name = std::filesystem::path(name).stem().string();
  return suite;
}

Suite load_suite(const std::string& name_or_path, const std::filesystem::path& config_dir) {
  std::filesystem::path file = name_or_path;
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) {
    if (name_or_path.find('/') != std::string::npos || file.has_extension()) {
      throw UsageError("--suite " + name_or_path + ": no such file");
    }
    file = config_dir / "suites" / (name_or_path + ".yaml");
    if (!std::filesystem::is_regular_file(file, error)) {
      throw UsageError("--suite " + name_or_path + ": no such suite (" + file.string() + ")");
    }
  }
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  return parse_suite(text.str(), file.string(), std::filesystem::absolute(file).parent_path());
}

}  // namespace omninav::evaluation
