#pragma once
// Turns what a user names on the command line into a World, with the parameters of
// worlds.yaml: a family of generated worlds, `family` or `family:key=value,...`
// (`room:seed=3,size_x_m=9,boxes=12,walls=plain`, `house:seed=2`, `field:tussocks=6000`,
// `office`), or a path to a Wavefront .obj file. docs/worlds.md lists every key.

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "omninav/sim/field.hpp"
#include "omninav/sim/house.hpp"
#include "omninav/sim/office.hpp"
#include "omninav/sim/renderer.hpp"
#include "omninav/sim/room.hpp"
#include "omninav/sim/world.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::sim {

struct WorldsConfig {
  RoomParams room;
  HouseParams house;
  FieldParams field;
  OfficeParams office;
  ObjWorldParams obj;
  RenderParams render;  // render.geometry comes from camera.yaml, not worlds.yaml
};

// Reads worlds.yaml (sections room, house, field, office, obj, render).
void load_worlds_config(const ConfigReader& config, WorldsConfig& worlds);

// The generated families, in the order help texts list them.
const std::vector<std::string>& world_families();

// True when `spec` names a Wavefront OBJ file rather than a family: it does not start with a
// family's name, and it ends in .obj (any case), contains a '/', or names an existing file.
bool is_obj_path(const std::string& spec);

// A world spec `family:key=value,...` split into its family and keys. Reading a key checks
// its value against the range (UsageError naming the spec, the key and the range); keys that
// were never read are reported by require_all_known(). The same reads as a ConfigReader's, so
// that one function reads a family's keys from worlds.yaml and from a spec.
class WorldSpec {
 public:
  // Throws UsageError for a missing family, a pair without '=', an empty key or a duplicate.
  explicit WorldSpec(const std::string& spec);

  const std::string& family() const { return family_; }

  void read(const std::string& key, double& value, double min, double max) const;
  void read(const std::string& key, int& value, int min, int max) const;
  void read(const std::string& key, std::string& value,
            const std::vector<std::string>& allowed) const;
  // Throws UsageError for the first key no read asked for, listing the known ones.
  void require_all_known() const;

 private:
  [[noreturn]] void fail(const std::string& message) const;
  const std::string* find(const std::string& key) const;
  // The key's value checked against [min, max] (and to be whole), or nothing when absent.
  std::optional<double> number(const std::string& key, double min, double max, bool whole) const;

  std::string spec_;
  std::string family_;
  std::map<std::string, std::string> values_;
  mutable std::set<std::string> asked_;
};

// A family spec (defaults from `worlds`, overridden by the spec's keys) or an OBJ path.
// Throws UsageError for a bad spec, InputError for an unreadable OBJ file.
World load_world(const std::string& spec, const WorldsConfig& worlds);

}  // namespace omninav::sim
