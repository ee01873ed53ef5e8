#pragma once
// A live session: the robot's frames pushed one at a time, each answered at once with what the
// libraries make of it, for a robot's middleware (apps/omninav_ros, docs/ros.md) and any other
// caller that receives frames as they come:
//   - the visual compass's heading and its standard deviation (compass::CompassRun, as
//     `omninav compass` runs it: the same frames give the same headings), started at the first
//     frame's odometry heading when it has one (the compass then shares the odometry's frame),
//     else at 0;
//   - with a map that has a lattice (omninav organise), the recognised place: the most probable
//     place of the belief over places (place_belief.hpp) over the map's confirmed links
//     (confirmed_links.hpp), its similarity (Eq. 3 over the map's places, 0..1000), the view's
//     dissimilarity per value to it and the belief's confidence (the share of the belief on it
//     and the places linked to it);
//   - while exploring, the place the frame became (memory::Explorer, as `omninav explore`);
//     save() writes the map through the map store (atomic: a failed save leaves the previous
//     map).
// The outputs depend on the frames, their order and their odometry only, never on when they
// arrive. A frame the session cannot use is skipped and counted, never thrown: an empty or
// non-8-bit image, a size other than the stream's first (or the map's rows), a stamp that is
// not after the last accepted one.
//
// The belief's motion model: with odometry, the distance driven since the last frame and its
// direction relative to the robot's heading then, added to the phases' heading of that frame in
// every place, moves the belief along the links (PlaceBelief::predict, as the navigator does
// with the motion it commands); a frame that did not move adds no evidence (the same view
// again). Without odometry, every frame is new evidence and the belief only mixes in its
// uniform share between frames.

#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "omninav/compass/compass_run.hpp"
#include "omninav/core/pose.hpp"
#include "omninav/lattice/confirmed_links.hpp"
#include "omninav/memory/memory_config.hpp"
#include "omninav/navigation/goal_navigation.hpp"
#include "omninav/navigation/place_belief.hpp"

namespace omninav::memory {
class Explorer;
class MapStore;
}  // namespace omninav::memory

namespace omninav::navigation {

// Everything a session reads from the configuration folder: compass.yaml, memory.yaml and
// navigation.yaml's sections (config/config_folder.hpp loads them).
struct LiveSessionParams {
  compass::CompassParams compass;
  std::optional<int> compass_width_px;  // compass.yaml's input.width_px
  memory::MemoryConfig memory;          // a new map's signature; exploration
  RouteParams route;
  NavigatorParams navigator;
  LinkParams links;
  BeliefParams belief;
};

struct LiveFrame {
  cv::Mat image;                  // a panorama (docs/design.md, Conventions), 8-bit BGR or grey
  double stamp_s = 0.0;           // capture time; must grow from frame to frame
  std::optional<Pose2> odometry;  // the robot's odometry at the stamp, when it has one
};

// The place the belief recognises in a frame.
struct LivePlace {
  memory::PlaceIndex place = 0;        // the most probable place
  double similarity = 0.0;             // Eq. 3 over the map's places: 1000 for the most similar
  double dissimilarity_per_value = 0;  // Eq. 6 per compared value, grey levels
  double probability = 0.0;            // the belief's on the place
  double confidence = 0.0;             // the belief's on the place and the places linked to it
  bool lost = false;                   // confidence below belief.confident_share
};

struct LiveOutput {
  int frame = 0;  // accepted frames before this one
  double stamp_s = 0.0;
  compass::CompassEstimate compass;
  std::optional<LivePlace> place;               // with a map that has a belief
  std::optional<memory::PlaceIndex> new_place;  // exploring: the place the frame became
};

// Why a frame was skipped.
enum class SkipReason { kBadImage, kSizeChange, kStamp };
inline constexpr int kSkipReasons = 3;
// "bad image", "size change", "stamp not increasing".
const char* to_string(SkipReason reason);

class LiveSession {
 public:
  // `map_file`: the map to recognise places in and to explore into, loaded when it exists (a
  // new map with memory.yaml's signature when it does not); none: no map (compass only, and
  // exploring into a map kept in memory that save() cannot write). Throws what loading throws
  // and UsageError for parameters out of range.
  LiveSession(LiveSessionParams params, std::optional<std::filesystem::path> map_file);
  ~LiveSession();
  LiveSession(const LiveSession&) = delete;
  LiveSession& operator=(const LiveSession&) = delete;

  // The frame's outputs; none when it was skipped (last_skip() says why, skipped() counts).
  // While exploring, throws what memory::Explorer::add throws (the frame counts as seen).
  std::optional<LiveOutput> push(const LiveFrame& frame);

  // Exploring: the frames pushed from now on go into a new run of the map, until stop.
  void start_exploring();
  void stop_exploring();
  bool exploring() const { return explorer_ != nullptr; }
  // Writes the map to map_file (memory::MapStore: what changed since the load or the last
  // save, in one transaction; a new map written whole). UsageError without a map file.
  void save();

  // Why the map gives no recognised places (none when it does): no map, no places, no lattice.
  const std::optional<std::string>& no_belief_reason() const { return no_belief_reason_; }
  int skipped(SkipReason reason) const { return skipped_[static_cast<int>(reason)]; }
  // The last skip's reason and a message that says what was wrong.
  const std::optional<std::pair<SkipReason, std::string>>& last_skip() const { return last_skip_; }
  const memory::VisualMemory& memory() const { return *memory_; }
  std::size_t place_count() const;

 private:
  // Whether the frame can be used; otherwise counts it and says why.
  bool accept(const LiveFrame& frame);
  std::optional<LivePlace> recognise(const cv::Mat& panorama, const std::optional<Pose2>& odometry);

  LiveSessionParams params_;
  std::optional<std::filesystem::path> map_file_;
  std::unique_ptr<memory::MapStore> store_;
  std::unique_ptr<memory::VisualMemory> memory_;
  std::unique_ptr<memory::Explorer> explorer_;
  compass::CompassRun compass_;
  // The belief over the places the map had when the session started (the places explored
  // since have no lattice position until the map is organised).
  std::optional<GoalNavigationSetup> setup_;
  std::unique_ptr<PlaceBelief> belief_;
  std::optional<std::string> no_belief_reason_;
  std::vector<double> dissimilarity_;  // the view's to every place, per value
  std::vector<double> in_place_;       // the last frame's heading relative to every place
  std::vector<double> motion_;         // the motion since the last frame, relative to each place
  std::optional<Pose2> last_odometry_;
  cv::Size size_;  // the stream's frames' (set by the first)
  int type_ = -1;
  std::optional<double> last_stamp_s_;
  int frames_ = 0;
  int explored_frames_ = 0;
  int skipped_[kSkipReasons] = {};
  std::optional<std::pair<SkipReason, std::string>> last_skip_;
};

}  // namespace omninav::navigation
