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
//   - navigating to a goal image (navigate_to), the command toward it: the navigator's
//     (goal_drive.hpp) on the frame it takes as its next view, what is left of that command on
//     the frames in between (below).
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
//
// Navigating, the navigator keeps its own belief, moved by its commands as in `navigate` (the
// recognised place above stays the session's). A command is a turn, then a drive. With
// odometry at the command's frame and at later frames, each later frame is answered with what
// is left of it (the turn is done once the odometry's heading, summed frame to frame, has
// turned by it, the drive once the odometry has moved by its distance from the command's
// frame), and the first frame at which both are done becomes the navigator's next view, with
// the distance the odometry moved; a frame at which the odometry's position has not changed
// since the last frame, the turn done before it, ends the command as blocked (the navigator's
// recovery then turns aside).
// Without odometry, each frame is the next view and the last command counts as carried out
// whole before it (a caller that acts on each command, then pushes the frame it then sees).

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
#include "omninav/navigation/goal_drive.hpp"
#include "omninav/navigation/goal_navigation.hpp"
#include "omninav/navigation/place_belief.hpp"

namespace omninav::memory {
class Explorer;
class Localiser;
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
  SteeringParams steering;  // compass.yaml's min_warping, camera.yaml's panorama
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

// Where navigating to a goal image stands after a frame.
enum class LiveNavigationState {
  kDriving,  // a command is under way
  kReached,  // the navigator stopped at the goal (navigate's `reached`): the robot stands still
  kFailed,   // navigator.max_steps views spent without reaching it: the robot stands still
};
// "driving", "reached", "failed".
const char* to_string(LiveNavigationState state);

// What the robot is to do after a frame while navigating: what is left of the navigator's
// command, the turn first, then the drive (both 0 once reached or failed).
struct LiveCommand {
  LiveNavigationState state = LiveNavigationState::kDriving;
  double turn_rad = 0.0;    // still to turn on the spot, counter-clockwise positive
  double distance_m = 0.0;  // still to drive forwards after the turn
  int step = 0;             // the navigator's step (view) the command is of
  bool new_step = false;    // this frame was that step's view
  NavigationPhase phase = NavigationPhase::kFollowingRoute;
  memory::PlaceIndex place = 0;  // the place the navigator acted on at that view
  bool lost = false;             // its belief was spread then (PlaceBelief::lost)
};

struct LiveOutput {
  int frame = 0;  // accepted frames before this one
  double stamp_s = 0.0;
  compass::CompassEstimate compass;
  std::optional<LivePlace> place;               // with a map that has a belief
  std::optional<memory::PlaceIndex> new_place;  // exploring: the place the frame became
  std::optional<LiveCommand> command;           // navigating (navigate_to)
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
  // Navigating: matches `goal_image` (named `what` in messages) to a place of the map, as
  // `omninav navigate` does, and answers the frames pushed from now on with a command toward it
  // (LiveOutput::command) until stop_navigating or another goal. Returns the goal's place.
  // InputError when the image matches no place or is not a panorama of the map's rows;
  // UsageError when the map recognises no places (no_belief_reason).
  memory::PlaceMatch navigate_to(const cv::Mat& goal_image, const std::string& what);
  void stop_navigating();
  bool navigating() const { return drive_ != nullptr; }

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
  // The frame's command while navigating (the class comment says which frames are views).
  std::optional<LiveCommand> command(const LiveFrame& frame);
  // Whether the command under way is done (or blocked) at `odometry`; sets what is left of it.
  bool command_done(const Pose2& odometry, LiveCommand& left);

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
  // Navigating: the goal image's localiser (made at the first goal), the navigator, and the
  // command under way with the odometry at its frame.
  std::unique_ptr<signature::SignatureExtractor> extractor_;
  std::unique_ptr<memory::Localiser> localiser_;
  std::unique_ptr<GoalDrive> drive_;
  struct CommandUnderWay {
    DriveCommand command;
    std::optional<Pose2> start;  // the odometry at the command's frame
    Pose2 last;                  // the odometry at the last frame
    double turned_rad = 0.0;     // the odometry's turn since the command's frame
    bool turned = false;         // the turn is done
  };
  std::optional<CommandUnderWay> under_way_;
  LiveCommand last_command_;
  cv::Size size_;  // the stream's frames' (set by the first)
  int type_ = -1;
  std::optional<double> last_stamp_s_;
  int frames_ = 0;
  int explored_frames_ = 0;
  int skipped_[kSkipReasons] = {};
  std::optional<std::pair<SkipReason, std::string>> last_skip_;
};

}  // namespace omninav::navigation
