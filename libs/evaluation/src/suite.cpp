#include "omninav/evaluation/suite.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/sim/world_loader.hpp"

namespace omninav::evaluation {
namespace {

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

namespace {

void read_suite_params(const ConfigReader& top, SuiteParams& p) {
  const ConfigReader panorama = top.section("panorama");
  panorama.read("width_px", p.width_px, 8, 16384);
  panorama.read("height_px", p.height_px, 1, 4096);
  const ConfigReader compass = top.section("compass");
  compass.read("fps", p.fps, 0.1, 1000.0);
  compass.read("rotate_turns", p.rotate_turns, 0.1, 100.0);
  compass.read("rotate_rate_deg_s", p.rotate_rate_deg_s, 0.1, 3600.0);
  compass.read("circle_radius_m", p.circle_radius_m, 0.01, 100.0);
  compass.read("speed_m_s", p.speed_m_s, 0.001, 100.0);
  compass.read("wander_length_m", p.wander_length_m, 0.1, 10000.0);
  compass.read("tilt_noise_deg", p.tilt_noise_deg, 0.0, 45.0);
  const ConfigReader memory = top.section("memory");
  memory.read("grid_nx", p.grid_nx, 2, 1000);
  memory.read("grid_ny", p.grid_ny, 2, 1000);
  memory.read("spacing_m", p.spacing_m, 0.001, 100.0);
  memory.read("queries", p.queries, 1, 1000000);
  const ConfigReader navigation = top.section("navigation");
  navigation.read("trials", p.trials, 1, 1000000);
  navigation.read("goal_radius_m", p.goal_radius_m, 0.01, 100.0);
  const ConfigReader tour = top.section("tour");
  tour.read("fps", p.tour_fps, 0.1, 1000.0);
  tour.read("turn_rate_deg_s", p.tour_turn_rate_deg_s, 0.0, 3600.0);
  tour.read("odometry_noise", p.odometry_noise, 0.0, 1.0);
}

// A suite's or a world's name becomes a folder and file names under evaluation/: letters,
// digits, '_', '-' and '.', not starting with '.', so that no name is a path ("../x", "/tmp").
void check_name(const ConfigReader& section, const std::string& name) {
  const bool plain =
      !name.empty() && name.front() != '.' && std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
      });
  if (!plain) {
    // Appended, not concatenated: GCC 12's -Wrestrict misfires on "'" + std::string here.
    std::string problem = printable_name(name);
    problem.insert(0, 1, '\'');
    problem += "' is not a name (letters, digits, '_', '-', '.'; no folders)";
    section.fail("name", problem);
  }
}

// One entry of `worlds:`: a row per seed and camera height, appended to `suite`. An OBJ path is
// relative to `base_dir`, the suite file's folder.
void add_world_rows(const ConfigReader& entry, const std::filesystem::path& base_dir, Suite& suite,
                    std::set<std::string>& labels) {
  const SuiteParams& p = suite.params;
  std::string label, spec;
  entry.read("name", label, {});
  entry.read("world", spec, {});
  if (spec.empty()) entry.fail("world", "is required: the --world spec");
  if (label.empty()) label = family_of(spec);
  check_name(entry, label);
  if (family_of(spec) == "obj" && !base_dir.empty() && std::filesystem::path(spec).is_relative()) {
    spec = (base_dir / spec).lexically_normal().string();
  }
  SuiteWorld row;
  row.family = family_of(spec);
  row.spacing_m = p.spacing_m;
  row.grid_nx = p.grid_nx;
  row.grid_ny = p.grid_ny;
  entry.read("spacing_m", row.spacing_m, 0.001, 100.0);
  entry.read("grid_nx", row.grid_nx, 2, 1000);
  entry.read("grid_ny", row.grid_ny, 2, 1000);
  entry.read("obj_scale_to_m", row.obj_scale_to_m, 1e-6, 1e6);
  std::vector<int> seeds;
  std::vector<double> heights{1.0};
  entry.read("seeds", seeds, 0, 1'000'000'000);
  entry.read("camera_heights_m", heights, 0.001, 100.0);
  const bool seeded = !seeds.empty();
  if (!seeded) seeds = {1};
  for (const int seed : seeds) {
    for (const double height : heights) {
      SuiteWorld world = row;
      world.spec = seeded ? with_key(spec, "seed", std::to_string(seed)) : spec;
      world.camera_height_m = height;
      world.seed = static_cast<std::uint32_t>(seed);
      world.label = label + (seeds.size() > 1 ? "-s" + std::to_string(seed) : "") +
                    (heights.size() > 1 ? height_label(height) : "");
      if (!labels.insert(world.label).second) {
        entry.fail("name", "gives two rows named '" + world.label + "': give the worlds names");
      }
      suite.worlds.push_back(world);
    }
  }
}

}  // namespace

Suite parse_suite(const std::string& yaml, const std::string& name,
                  const std::filesystem::path& base_dir) {
  const ConfigReader top = ConfigReader::from_string(yaml, name);
  Suite suite;
  suite.file = name;
  top.read("name", suite.name, {});
  read_suite_params(top, suite.params);
  const std::vector<ConfigReader> worlds = top.sections("worlds");
  if (worlds.empty()) top.fail("worlds", "is required: a non-empty list of worlds");
  std::set<std::string> labels;
  for (const ConfigReader& entry : worlds) add_world_rows(entry, base_dir, suite, labels);
  top.require_all_known();
  if (suite.name.empty()) suite.name = std::filesystem::path(name).stem().string();
  check_name(top, suite.name);
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
  return parse_suite(text.str(), file.string(),
                     std::filesystem::weakly_canonical(file).parent_path());
}

}  // namespace omninav::evaluation
