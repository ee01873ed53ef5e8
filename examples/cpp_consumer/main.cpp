// A program outside omninav that links the installed package (omninav::memory and what it
// brings): it explores three synthetic panoramas into a map, saves it, reads it back and
// localises the second panorama as the robot sees it after a quarter turn. It writes the map and
// the query image to the folder it is given, so that the installed `omninav` can read them too.
// Given a configuration folder (the installed share/omninav/config), it localises with its
// memory.yaml, read by omninav::memory's own loader.
//
//   omninav_consumer OUT_DIR [CONFIG_DIR]   ->  OUT_DIR/map.vmem, OUT_DIR/query.png
//
// Exit status 0 when the query is localised at place 1 turned by 90 degrees, 1 otherwise.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/memory/exploration.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/memory/memory_config.hpp"
#include "omninav/signature/signature.hpp"

namespace {

// A smooth random grey panorama, 256 x 64, different for every seed.
cv::Mat synthetic_panorama(int seed) {
  cv::Mat noise(64, 256, CV_8UC1);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::Mat smooth;
  cv::GaussianBlur(noise, smooth, cv::Size(0, 0), 4.0);
  cv::normalize(smooth, smooth, 0, 255, cv::NORM_MINMAX);
  return smooth;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) {
    std::cerr << "usage: omninav_consumer OUT_DIR [CONFIG_DIR]\n";
    return 2;
  }
  namespace fs = std::filesystem;
  using namespace omninav;
  const fs::path out = argv[1];
  try {
    fs::create_directories(out);
    std::vector<cv::Mat> panoramas{synthetic_panorama(1), synthetic_panorama(2),
                                   synthetic_panorama(3)};

    // Every panorama a place of a new map (explore --all-frames).
    memory::VisualMemory map;
    std::size_t next = 0;
    const memory::Run run = memory::explore_frames(map, {},
                                                   {.name = "synthetic panoramas",
                                                    .all_frames = true,
                                                    .frame_count = panoramas.size(),
                                                    .next = [&]() -> std::optional<io::Frame> {
                                                      if (next == panoramas.size())
                                                        return std::nullopt;
                                                      io::Frame frame;
                                                      frame.index = static_cast<int>(next);
                                                      frame.image = panoramas[next];
                                                      frame.source =
                                                          "synthetic " + std::to_string(next++);
                                                      return frame;
                                                    }});
    const fs::path map_file = out / "map.vmem";
    memory::MapStore(map_file).save(map, {.overwrite = true, .after_place = {}});

    // The robot back at place 1, turned a quarter turn counter-clockwise.
    const int width = panoramas[1].cols;
    const cv::Mat query = roll_columns(panoramas[1], width / 4);
    cv::imwrite((out / "query.png").string(), query);

    const memory::VisualMemory loaded = memory::load_map(map_file);
    memory::LocalisationParams localisation;
    if (argc == 3) {
      localisation =
          memory::load_memory_config(ConfigReader::from_file(fs::path(argv[2]) / "memory.yaml"))
              .localisation;
    }
    const memory::Localiser localiser(loaded, localisation);
    const memory::Localisation result =
        localiser.localise(signature::compute_signature(query, loaded.parameters().signature));
    if (result.best.empty()) {
      std::cerr << "no place matched\n";
      return 1;
    }
    const memory::PlaceMatch& best = result.best.front();
    const double turn_deg = best.relative_heading_rad * 180.0 / std::numbers::pi;
    std::cout << "map " << map_file.string() << ": " << run.places << " places; query at place "
              << best.place << ", turned " << turn_deg << " deg\n";
    return best.place == 1 && std::abs(turn_deg - 90.0) < 2.0 ? 0 : 1;
  } catch (const std::exception& error) {
    std::cerr << "omninav_consumer: " << error.what() << "\n";
    return 1;
  }
}
