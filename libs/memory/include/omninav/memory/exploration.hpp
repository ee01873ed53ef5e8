#pragma once
// Exploration (001_5bb151a4e28490b4.txt §3.1): a stream of panoramas becomes places of the
// visual memory. A frame becomes a new place when
//   - it is the first of the run, or
//   - its dissimilarity to the last place, per compared value, reaches
//     new_place_dissimilarity (the view has changed enough), or
//   - every_n_frames frames have passed since the last place, or
//   - every_m metres were travelled since the last place (only when the input has poses);
// (each rule off when its value is 0). Each new place gets an edge from the previous place of
// the run with their relative heading (phases, Eq. 1) and direction of motion (§3.4).

#include <optional>
#include <string>

#include "omninav/io/frame.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::memory {

struct ExplorationParams {
  // Mean |Δ magnitude| per compared value (Dis of Eq. 6 divided by lines × components), grey
  // levels, that makes a new place; 0: off. On the rendered 30 cm grid of the built-in room,
  // neighbours 30 cm apart differ by 1.85 (median; 10th percentile 1.42, luminance, m = 15;
  // docs/memory.md, Fig. 7): 1.5 makes places about 30 cm apart or closer.
  double new_place_dissimilarity = 1.5;
  int every_n_frames = 0;        // a place at least every n frames; 0: off
  double every_m = 0.0;          // a place every d metres travelled (poses needed); 0: off
  int thumbnail_width_px = 180;  // thumbnails keep the panorama's aspect ratio
  // Where headings come from: "auto" (the ground truth when a frame has it, else none),
  // "truth" (required) or "none". The visual compass will add "compass".
  std::string heading_source = "auto";
  // Components used to measure the direction of motion (§3.4, signature/motion.hpp); 0: the
  // signature's.
  int motion_components = 0;
};

// Reads the `exploration:` section of memory.yaml.
void load_exploration_params(const ConfigReader& section, ExplorationParams& params);

class Explorer {
 public:
  // Starts a new run in `memory` (which may already hold places: exploring extends it). The
  // memory must outlive the explorer.
  Explorer(VisualMemory& memory, ExplorationParams params, std::string input,
           std::string description);

  // Considers one frame whose image is a panorama; returns the new place's index when the
  // frame became one. Throws InputError naming frame.source for a bad image, UsageError when
  // heading_source is "truth" and the frame has no pose.
  std::optional<PlaceIndex> add(const io::Frame& frame);

  // Forces the frame to become a place (e.g. every image of a grid database).
  PlaceIndex add_place(const io::Frame& frame);

  const Run& run() const;
  int frames_seen() const { return frames_; }

 private:
  PlaceIndex make_place(const io::Frame& frame, const signature::Signature& signature);

  VisualMemory& memory_;
  ExplorationParams params_;
  signature::SignatureExtractor extractor_;
  std::size_t run_index_;
  std::optional<PlaceIndex> last_place_;
  int frames_ = 0;
  int frames_since_place_ = 0;
  double metres_since_place_ = 0.0;
  std::optional<CameraPose> previous_pose_;
};

// The thumbnail stored with a place: the panorama scaled to `width_px` wide, PNG-encoded.
std::vector<std::uint8_t> make_thumbnail(const cv::Mat& panorama, int width_px);

}  // namespace omninav::memory
