#include "omninav/sim/world_loader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/parse.hpp"

namespace omninav::sim {
namespace {

// "[min, max]".
std::string range_text(double min, double max) {
  return fmt::format("[{}, {}]", general(min), general(max));
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

// The room's keys on the command line: the zoo's range for rooms (3-12 m sides,
// 0-20 boxes, plain or textured walls). worlds.yaml keeps its own, wider keys.
void read_room_spec(const WorldSpec& spec, RoomParams& params) {
  spec.read("size_x_m", params.size_x_m, 3.0, 12.0);
  spec.read("size_y_m", params.size_y_m, 3.0, 12.0);
  spec.read("height_m", params.height_m, 2.0, 5.0);
  spec.read("boxes", params.furniture_count, 0, 20);
  std::string walls = params.plain_walls ? "plain" : "textured";
  spec.read("walls", walls, {"plain", "textured"});
  params.plain_walls = walls == "plain";
  int seed = static_cast<int>(params.seed);
  spec.read("seed", seed, 0, 1'000'000'000);
  params.seed = static_cast<std::uint32_t>(seed);
}

}  // namespace

void load_worlds_config(const ConfigReader& config, WorldsConfig& worlds) {
  load_room_params(config.section("room"), worlds.room);
  read_house_keys(config.section("house"), worlds.house);
  read_field_keys(config.section("field"), worlds.field);
  read_office_keys(config.section("office"), worlds.office);
  const ConfigReader obj = config.section("obj");
  obj.read("y_up", worlds.obj.y_up);
  obj.read("scale_to_m", worlds.obj.scale_to_m, 1e-6, 1e6);
  load_render_params(config.section("render"), worlds.render);
}

const std::vector<std::string>& world_families() {
  static const std::vector<std::string> families{"room", "house", "field", "office"};
  return families;
}

bool is_obj_path(const std::string& spec) {
  const std::string family(trim(spec.substr(0, spec.find(':'))));
  const std::vector<std::string>& families = world_families();
  if (std::find(families.begin(), families.end(), family) != families.end()) return false;
  std::string lower = spec;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower.size() >= 4 && lower.ends_with(".obj")) return true;
  if (spec.find('/') != std::string::npos) return true;
  std::error_code error;
  return std::filesystem::is_regular_file(spec, error);
}

WorldSpec::WorldSpec(const std::string& spec) : spec_(spec) {
  const std::size_t colon = spec.find(':');
  family_ = std::string(trim(spec.substr(0, colon)));
  if (family_.empty()) fail("no world family before the ':'");
  if (colon == std::string::npos || trim(spec.substr(colon + 1)).empty()) return;
  for (const std::string& pair : split(spec.substr(colon + 1), ',')) {
    const std::size_t equals = pair.find('=');
    if (equals == std::string::npos) fail("expected key=value, got '" + pair + "'");
    std::string key(trim(pair.substr(0, equals)));
    if (key.empty()) fail("a key is missing before '=' in '" + pair + "'");
    if (values_.contains(key)) fail("key '" + key + "' is given twice");
    values_[std::move(key)] = std::string(trim(pair.substr(equals + 1)));
  }
}

void WorldSpec::fail(const std::string& message) const {
  throw UsageError("world '" + spec_ + "': " + message);
}

const std::string* WorldSpec::find(const std::string& key) const {
  asked_.insert(key);
  const auto found = values_.find(key);
  return found == values_.end() ? nullptr : &found->second;
}

std::optional<double> WorldSpec::number(const std::string& key, double min, double max,
                                        bool whole) const {
  const std::string* text = find(key);
  if (!text) return std::nullopt;
  const std::string range = " (valid: " + range_text(min, max) + ")";
  const std::string kind = whole ? "a whole number" : "a finite number";
  double parsed = 0.0;
  try {
    parsed = parse_double(*text, key);
  } catch (const InputError&) {
    fail(key + " = '" + *text + "' is not " + kind + range);
  }
  if (whole && parsed != std::floor(parsed)) fail(key + " = " + *text + " is not " + kind + range);
  if (parsed < min || parsed > max) fail(key + " = " + *text + " is out of range" + range);
  return parsed;
}

void WorldSpec::read(const std::string& key, double& value, double min, double max) const {
  if (const std::optional<double> parsed = number(key, min, max, false)) value = *parsed;
}

void WorldSpec::read(const std::string& key, int& value, int min, int max) const {
  if (const std::optional<double> parsed = number(key, min, max, true)) {
    value = static_cast<int>(*parsed);
  }
}

void WorldSpec::read(const std::string& key, std::string& value,
                     const std::vector<std::string>& allowed) const {
  const std::string* text = find(key);
  if (!text) return;
  if (std::find(allowed.begin(), allowed.end(), *text) == allowed.end()) {
    fail(key + " = '" + *text + "' is not one of " + joined(allowed));
  }
  value = *text;
}

void WorldSpec::require_all_known() const {
  for (const auto& [key, value] : values_) {
    if (asked_.contains(key)) continue;
    fail("unknown key '" + key + "' for " + family_ +
         " (keys: " + joined(std::vector<std::string>(asked_.begin(), asked_.end())) + ")");
  }
}

World load_world(const std::string& spec, const WorldsConfig& worlds) {
  if (is_obj_path(spec)) return load_obj_world(spec, worlds.obj);
  const WorldSpec keys(spec);
  World world;
  if (keys.family() == "room") {
    RoomParams params = worlds.room;
    read_room_spec(keys, params);
    keys.require_all_known();
    world = make_room(params);
  } else if (keys.family() == "house") {
    HouseParams params = worlds.house;
    read_house_keys(keys, params);
    keys.require_all_known();
    world = make_house(params);
  } else if (keys.family() == "field") {
    FieldParams params = worlds.field;
    read_field_keys(keys, params);
    keys.require_all_known();
    world = make_field(params);
  } else if (keys.family() == "office") {
    OfficeParams params = worlds.office;
    read_office_keys(keys, params);
    keys.require_all_known();
    world = make_office(params);
  } else {
    throw UsageError("world '" + spec + "': unknown family '" + keys.family() + "' (" +
                     joined(world_families()) + ", or a path to a Wavefront .obj file)");
  }
  world.name = spec;
  return world;
}

}  // namespace omninav::sim
