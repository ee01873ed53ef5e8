#pragma once
// Exploration (Menegatti et al. 2004, §3.1): a stream of panoramas becomes places of the
// visual memory. A frame becomes a new place when
//   - it is the first of the run, or
//   - its dissimilarity to the last place, per compared value, reaches
//     new_place_dissimilarity (the view has changed enough; "auto": a share of the plateau,
//     below), or
//   - every_n_frames frames have passed since the last place, or
//   - every_m metres were travelled since the last place (only when the input has poses, or
//     with `odometry` its odometry; the map then records it, VisualMemory::exploration_spacing_m,
//     the lattice's default scale);
// (each rule off when its value is 0). Each new place gets an edge from the previous place of
// the run with their relative heading (phases, Eq. 1) and direction of motion (§3.4): of kind
// sequence along a stream, listed for an unordered input (visual_memory.hpp).
//
// The new-place threshold "auto" (new_place_dissimilarity none; the default, see below). A
// fixed number of grey levels spaces places differently in every world: what a 30 cm step costs
// ranges from 1 (a field seen from 1 m) to 4.6 (the Ofstad arena) per value (docs/memory.md). So
// the threshold is derived from the stream itself, as a share (new_place_plateau_share) of the
// plateau of Fig. 7, the level the dissimilarity saturates at between views far apart: places come
// a fixed share of the way to the plateau apart, wherever that lies in metres. The plateau is the
// lattice's (signature/plateau.hpp: the 90th percentile of pairs), estimated while exploring from
// frames sampled evenly over the stream so far (PlateauEstimate), so that it works on a stream
// seen once (a camera): the estimate grows as the robot covers ground, so places come somewhat
// closer early in a run. No place is made by dissimilarity before the estimate holds
// kAutoWarmupFrames frames (the run's first frame is a place as always). Exploring into a map,
// the estimate starts from the map's places.
//
// A plateau is evidence of travel only when the threshold it gives stands above the floor: what
// two frames of one spot differ by (signature/plateau.hpp). On a stream that never leaves its
// spot (a turn on the spot, a camera standing still) the pairs far apart in time differ by the
// same noise as neighbours, and a share of that plateau would make a place of nearly every
// frame. The floor is read from the steps between consecutive frames that a turn on the spot
// explains: the compass's pair matcher (libs/compass) finds the rotation between them, and what
// that rotation leaves unexplained is no more than rolling the image by half a column leaves
// (the most a turn can: its rotation lies within half a column of a whole shift). Steps with
// more (parallax: the frames are of two spots) say nothing about the floor, so a stream whose
// every step travels, however far, has no floor and keeps the threshold; the signatures alone
// cannot tell such a stream (grass passing a lens 10 cm above it) from noise, since both differ
// as much between neighbours as far apart. While the threshold is within the floor, no place is
// made by dissimilarity: one spot, one place (the run's first frame).
//
// Headings. heading_source "auto" (the default) is "compass" for a stream and, for an unordered
// input (a grid database) that records its images' headings, "truth": the database's own
// headings, because the compass does worse there (below). The map says which, per place.
//
// heading_source "compass": every frame of a stream, place or not,
// goes through the visual compass (Labrosse 2006, Algorithm 1; libs/compass), and a
// place keeps the compass heading of its frame. Where the compass's 0 lies is a choice of gauge:
//   - exploring into a map whose places have headings: the new run starts at the heading of the
//     existing place most like its first frame plus their relative heading from the phases
//     (Menegatti et al. 2004, Eq. 1), so that the runs share one heading frame;
//   - otherwise at the first frame's ground-truth heading when the input has one (as Labrosse 2006,
//   §4.1,
//     does "to allow comparison"; it only places 0, so that headings can be checked against the
//     truth), else at 0: the first frame's front.
// Every change of heading after that is measured by the compass alone.
//
// An unordered input (a grid database: its order says nothing about where the images were
// taken, and a raster's row ends jump metres) is no stream for Algorithm 1, whose reference is
// the previous frame, whose errors grow where a raster jumps. So each image is matched instead
// with the most similar place seen before it (by the signature dissimilarity) and takes that
// place's heading plus the rotation the compass's pair matcher measures between them, started
// at the phases' estimate. Beyond the paper, which explores along a route: a step sideways
// moves the front and back bands of the field of view (§3.4.3) in opposite directions by
// amounts that differ with the depth in front and behind, and biases the match. So both images
// are first rolled so that the direction of the step (§3.4, from the phases) lies at the second
// image's front: the bands then sit where the step moves nothing, as they do for a robot
// driving forwards, and rolling both by the same amount leaves their relative rotation
// unchanged. docs/memory.md (Place headings) compares the three ways on rendered grids and
// says how to measure them; tests/memory/exploration_test.cpp guards the errors.

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "omninav/compass/visual_compass.hpp"
#include "omninav/io/frame.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/signature/plateau.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::memory {

// Where a run's headings come from (see the headings above): kAuto settles on compass or truth
// by the input at its first frame; each of the others is the HeadingSource of its places.
enum class HeadingPolicy { kAuto, kCompass, kTruth, kNone };
std::string to_string(HeadingPolicy policy);
// "auto", "compass", "truth" or "none"; throws UsageError otherwise.
HeadingPolicy heading_policy_from_string(const std::string& text);

struct ExplorationParams {
  // Mean |Δ magnitude| per compared value (Dis of Eq. 6 divided by lines × components), grey
  // levels, that makes a new place; 0: off. None ("auto" in memory.yaml, the default):
  // new_place_plateau_share × the stream's plateau (above). The default is chosen across the zoo
  // leaving one family out, as the sparsest map whose worst family localises >= 95% of queries
  // within 0.3 m: auto at 0.25 of the plateau (four folds of five; docs/memory.md, "The
  // new-place threshold"). The built-in room's fixed 1.5 (its neighbours 30 cm apart differ by
  // 1.85) localises the field's zig-zag maps 0.805.
  std::optional<double> new_place_dissimilarity = std::nullopt;
  double new_place_plateau_share = 0.25;
  int every_n_frames = 0;  // a place at least every n frames; 0: off
  double every_m = 0.0;    // a place every d metres travelled (poses needed); 0: off
  // Where the distance travelled comes from: false, the input's poses (Frame::truth); true, the
  // robot's own odometry recorded beside them (Frame::odometry: a BoB database's Odometry
  // columns, a CSV's odometry_* columns, a bag's --pose-topic), as a robot without ground truth
  // measures it (explore --odometry).
  bool odometry = false;
  int thumbnail_width_px = 180;  // thumbnails keep the panorama's aspect ratio
  // Where headings come from: auto (above), compass (the visual compass, above), truth (the
  // input's poses, required) or none.
  HeadingPolicy heading_source = HeadingPolicy::kAuto;
  // The visual compass used by heading_source "compass" (config/compass.yaml), and the width its
  // panoramas are resampled to first (absent: their own width).
  compass::CompassParams compass;
  std::optional<int> compass_width_px;
  // Components used to measure the direction of motion (§3.4, signature/motion.hpp); 0: the
  // signature's.
  int motion_components = 0;

  // The ranges of memory.yaml's exploration section. Throws UsageError naming the key
  // (core/param_check.hpp); the loader and Explorer's constructor call it.
  void check() const;
};

// Reads the `exploration:` section of memory.yaml.
void load_exploration_params(const ConfigReader& section, ExplorationParams& params);

// How the frames given to an Explorer relate to each other (see the headings above).
enum class FrameOrder {
  kStream,     // a continuous run: video, route, rendered trajectory
  kUnordered,  // a set of images, such as a grid database
};

class Explorer {
 public:
  // With the threshold auto, frames the plateau estimate must hold before it makes places: with
  // fewer, the few pairs' noise sets it. After that, places come at about frames 8, 16, 32, ...
  // while the robot covers ground faster than views saturate (the estimate then grows as the
  // span of the stream does), then at the share of the plateau.
  static constexpr std::size_t kAutoWarmupFrames = 8;

  // Starts a new run in `memory` (which may already hold places: exploring extends it). The
  // memory must outlive the explorer.
  Explorer(VisualMemory& memory, ExplorationParams params, std::string input,
           std::string description, FrameOrder order = FrameOrder::kStream);

  // Considers one frame whose image is a panorama; returns the new place's index when the
  // frame became one. Throws InputError naming frame.source for a bad image or one whose shape
  // differs from the run's first, UsageError when heading_source is "truth" and the frame has
  // no pose, InputError when with every_m set the poses travelled (or the odometry, with
  // `odometry`) move more than 2 × every_m between two frames (a jump).
  std::optional<PlaceIndex> add(const io::Frame& frame);

  // Forces the frame to become a place (e.g. every image of a grid database).
  PlaceIndex add_place(const io::Frame& frame);

  const Run& run() const;
  int frames_seen() const { return frames_; }
  // The dissimilarity per value that makes a new place now: new_place_dissimilarity, or with
  // new_place_auto the share of the plateau estimated so far (none during the warm-up, and
  // while it is within the floor: no travel seen); none when the rule is off.
  std::optional<double> new_place_threshold() const;
  // With new_place_auto, the plateau estimated so far (per value), and the floor: what
  // consecutive frames differ by at their closest (signature/plateau.hpp).
  std::optional<double> plateau_per_value() const;
  std::optional<double> floor_per_value() const;
  // With new_place_auto, whether the threshold is within the floor: no travel seen (above).
  bool threshold_within_floor() const;

 private:
  // Feeds the frame to the visual compass (heading_source "compass"; otherwise does nothing):
  // Algorithm 1 along a stream, a match with the most similar earlier place when unordered.
  void track_heading(const io::Frame& frame, const signature::Signature& signature);
  double heading_from_nearest_place(const cv::Mat& panorama,
                                    const signature::Signature& signature) const;
  // The place among [begin, end) that has a heading and is most like `signature`, if any.
  std::optional<PlaceIndex> most_similar_place(const signature::Signature& signature,
                                               PlaceIndex begin, PlaceIndex end) const;
  // Where the compass starts for the run's first frame (the gauge, see above).
  double initial_heading(const io::Frame& frame, const signature::Signature& signature) const;
  PlaceIndex make_place(const io::Frame& frame, const signature::Signature& signature);
  // The distance from the previous frame's pose (0 for the first); throws on a jump (see add).
  double travelled_step_m(const std::optional<CameraPose>& travelled,
                          const std::string& source) const;
  // The panorama resampled to the compass's width (compass_width_px), or itself.
  cv::Mat at_compass_width(const cv::Mat& panorama) const;
  // Whether the step from previous_panorama_ to `panorama` (both at compass width) is a turn on
  // the spot: what the compass cannot explain by a rotation is no more than a turn leaves.
  bool is_turn_on_the_spot(const cv::Mat& panorama);

  VisualMemory& memory_;
  ExplorationParams params_;
  signature::SignatureExtractor extractor_;
  std::size_t run_index_;
  std::optional<PlaceIndex> last_place_;
  int frames_ = 0;
  int places_ = 0;  // added by this run
  int frames_since_place_ = 0;
  double metres_since_place_ = 0.0;
  std::optional<CameraPose> previous_pose_;
  std::size_t places_before_run_ = 0;  // places of earlier runs (candidates for the gauge)
  FrameOrder order_;
  std::optional<HeadingSource> heading_source_;  // params_.heading_source; auto: at the first frame
  std::unique_ptr<compass::VisualCompass> compass_;      // streams
  std::unique_ptr<compass::PairMatcher> place_matcher_;  // unordered inputs
  std::vector<cv::Mat> run_place_panoramas_;  // unordered: this run's places, at compass width
  double compass_heading_rad_ = 0.0;  // the compass's heading of the latest frame (unwrapped)
  std::unique_ptr<signature::PlateauEstimate> plateau_;  // new_place_auto
  // new_place_auto: the last frame at compass width, while the next frame's step will count for
  // the plateau's floor, and the matcher that judges that step.
  cv::Mat previous_panorama_;
  std::unique_ptr<compass::PairMatcher> step_matcher_;
  bool plateau_from_map_ = false;  // the estimate started from the places of the map extended
};

// The frames `omninav explore` takes into a run.
struct ExplorationInput {
  std::string name;  // as the user gave it: the run's description and error messages
  // A grid database (unordered, kUnordered): every frame is a place.
  bool is_grid = false;
  bool all_frames = false;      // every frame a place, whatever the exploration rules say
  std::size_t frame_count = 0;  // for the progress line only (0: unknown)
  // The distance between neighbouring points of a grid database, when it states it
  // (io::SequenceReader::grid_spacing_m): recorded in the map as its scale.
  std::optional<double> grid_spacing_m;
  std::function<std::optional<io::Frame>()> next;  // the next frame; nothing at the end
};

// What `omninav explore` does with an input, for the command and for `omninav evaluate`:
// every frame of `input` goes into a new run of `memory`; a grid database or `all_frames`
// makes every frame a place, otherwise the exploration rules of `params` decide. Returns the
// run (frames read, places added, heading source). Throws InputError when the input had no
// frames, and what Explorer::add throws.
Run explore_frames(VisualMemory& memory, const ExplorationParams& params,
                   const ExplorationInput& input);

}  // namespace omninav::memory
