#pragma once
// A suite of `omninav evaluate`: the worlds to measure and how (config/suites/*.yaml documents
// every key). Each world entry expands into one row per seed and camera height.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace omninav::evaluation {

// How every world of the suite is measured. Lengths in metres are for a world measured at the
// suite's spacing; a world with its own spacing_m has them scaled by spacing_m / spacing_m.
struct SuiteParams {
  // The panoramas rendered (the commands' render --width/--height/--rays-per-pixel).
  // (Rays per pixel are worlds.yaml's, as `navigate` has no option for them.)
  int width_px = 360;
  int height_px = 45;
  // Compass routes (Labrosse 2006, Tables 3-4).
  double fps = 10.0;                // frames per second of every route
  double rotate_turns = 3.0;        // on-the-spot rotation
  double rotate_rate_deg_s = 30.0;  // its turning speed
  double circle_radius_m = 1.0;     // largest circle radius (smaller where furniture is near)
  double speed_m_s = 0.2;           // circle, wander, saccadic route and zig-zag speed
  double wander_length_m = 8.0;     // the wandering route's length, the saccadic route's travel
  double tilt_noise_deg = 2.0;      // pitch and roll noise of the bumpy wander
  // Memory: a grid explored, queries localised.
  int grid_nx = 10;
  int grid_ny = 8;
  double spacing_m = 0.3;
  int queries = 100;
  // Navigation, on the grid map and on the driven map.
  int trials = 50;
  double goal_radius_m = 0.3;  // reached: the robot stops within this of the goal's position
  // The driven map: a `tour` of the grid's rectangle (lanes a spacing apart, the robot's radius
  // kept from obstacles, at speed_m_s), explored with a place every spacing by its odometry.
  double tour_fps = 5.0;               // frames per second along the tour
  double tour_turn_rate_deg_s = 45.0;  // turning on the spot at lane ends and corners
  double odometry_noise = 0.05;        // relative error of odometry's distances and turns
};

// One row of the table.
struct SuiteWorld {
  std::string label;   // the row's name, e.g. "room-s2-h10cm"
  std::string family;  // room, house, field, office or obj
  std::string spec;    // what --world takes
  double camera_height_m = 1.0;
  double spacing_m = 0.3;  // the grid's spacing in this world
  int grid_nx = 10;        // the grid's size (at most: it is shrunk to fit the floor)
  int grid_ny = 8;
  double obj_scale_to_m = 0.0;  // OBJ worlds: worlds.yaml's obj.scale_to_m instead (0: keep)
  std::uint32_t seed = 1;       // of the queries, trials and the wander (and the world's own seed)
};

struct Suite {
  std::string name;
  std::filesystem::path file;
  SuiteParams params;
  std::vector<SuiteWorld> worlds;
};

// `name_or_path`: a YAML file, or the name of one in <config_dir>/suites/ (quick, full).
// Throws ConfigError naming the file and key for an unknown key or a bad value, UsageError for
// an unknown suite name.
Suite load_suite(const std::string& name_or_path, const std::filesystem::path& config_dir);

// The same from YAML text (`name` in messages). A relative OBJ path is taken relative to
// `base_dir` (load_suite: the suite file's folder) when one is given.
Suite parse_suite(const std::string& yaml, const std::string& name,
                  const std::filesystem::path& base_dir = {});

// The family of a world spec: the text before ':' (`room`, `field`, ...), "obj" for a path.
std::string family_of(const std::string& spec);

}  // namespace omninav::evaluation
