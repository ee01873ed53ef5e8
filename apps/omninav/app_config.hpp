#pragma once
// The configuration folder's loaders (libs/config, config_folder.hpp), which the commands name
// unqualified.

#include <CLI/CLI.hpp>
#include <filesystem>

#include "omninav/config/config_folder.hpp"
#include "omninav/io/bag_sequence.hpp"
#include "omninav/io/panorama_input.hpp"

namespace omninav::cli {

using config::load_camera_config;
using config::load_compass_config;
using config::load_lattice_config;
using config::load_memory_config;
using config::load_navigation_config;
using config::load_worlds_config;
using config::use_compass_config;
using evaluation::CameraConfig;
using evaluation::NavigationConfig;

// The frames of `input` as panoramas; raw omnidirectional images are unwrapped with the
// `unwrap:` section of camera.yaml in `config_dir`, read at the first frame that needs it.
inline io::PanoramaInput open_panoramas(const std::filesystem::path& input,
                                        const std::filesystem::path& config_dir,
                                        io::PanoramaInputOptions options = {}) {
  return io::PanoramaInput(
      input, [config_dir] { return load_camera_config(config_dir).unwrap; }, options);
}

// --topic and --pose-topic, for the commands that read a sequence that may be a bag.
inline void add_bag_options(CLI::App* command, io::BagOptions& bag) {
  command->add_option("--topic", bag.topic,
                      "A bag's image topic (sensor_msgs/Image or CompressedImage); needed only "
                      "when the bag has several (docs/bags.md)");
  command->add_option("--pose-topic", bag.pose_topic,
                      "A bag's pose topic (nav_msgs/Odometry or geometry_msgs/PoseStamped): the "
                      "frames' poses, interpolated at their stamps");
}

// The help of a --world option, the same in every command that renders.
inline constexpr const char* kWorldOptionHelp =
    "A world family, with optional keys overriding worlds.yaml: family[:key=value,...], "
    "or a Wavefront .obj file. Families:\n"
    "  room (size_x_m, size_y_m 3-12, height_m, boxes 0-20, walls plain|textured, seed)\n"
    "  house (rooms 2-10, room_min_m, room_max_m, corridor_width_m, door_width_m, height_m, "
    "furniture, seed): rooms of different looks joined by doorways and a corridor\n"
    "  field (size_m, tussocks, grass_min_m, grass_max_m, bushes, trees, rocks, "
    "horizon trees|hills|none, seed): grass tussocks, bushes, trees, hills and sky\n"
    "  office (rows, desks_per_row, desk_pitch_m, row_pitch_m, column_every, height_m, "
    "clutter 0-1, seed): identical desks at a regular pitch\n"
    "Example: room:seed=3,size_x_m=9,boxes=12,walls=plain (docs/worlds.md lists every key)";

}  // namespace omninav::cli
