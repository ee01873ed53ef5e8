#include "omninav/memory/exploration.hpp"

#include <chrono>
#include <cmath>
#include <ctime>
#include <sstream>

#include "omninav/compass/resample.hpp"
#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/core/param_check.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/core/progress.hpp"
#include "omninav/memory/thumbnail.hpp"
#include "omninav/signature/dissimilarity.hpp"
#include "omninav/signature/motion.hpp"
#include "omninav/signature/phase_heading.hpp"

namespace omninav::memory {

std::string to_string(HeadingPolicy policy) {
  switch (policy) {
    case HeadingPolicy::kCompass:
      return "compass";
    case HeadingPolicy::kTruth:
      return "truth";
    case HeadingPolicy::kNone:
      return "none";
    case HeadingPolicy::kAuto:
      break;
  }
  return "auto";
}

HeadingPolicy heading_policy_from_string(const std::string& text) {
  if (text == "auto") return HeadingPolicy::kAuto;
  if (text == "compass") return HeadingPolicy::kCompass;
  if (text == "truth") return HeadingPolicy::kTruth;
  if (text == "none") return HeadingPolicy::kNone;
  throw UsageError("heading source '" + text + "' is not one of: auto, compass, truth, none");
}

void load_exploration_params(const ConfigReader& section, ExplorationParams& params) {
  // auto or a number of grey levels.
  std::string threshold;
  section.read("new_place_dissimilarity", threshold, {});
  if (threshold == "auto") {
    params.new_place_dissimilarity.reset();
  } else if (!threshold.empty()) {
    double value = 0.0;
    try {
      section.read("new_place_dissimilarity", value);
      params.new_place_dissimilarity = value;
    } catch (const ConfigError&) {
      section.fail("new_place_dissimilarity",
                   "= '" + threshold + "' is neither auto nor a number in [0, 1000]");
    }
  }
  section.read("new_place_plateau_share", params.new_place_plateau_share);
  section.read("every_n_frames", params.every_n_frames);
  section.read("every_m", params.every_m);
  section.read("thumbnail_width_px", params.thumbnail_width_px);
  std::string heading_source = to_string(params.heading_source);
  section.read("heading_source", heading_source, {"auto", "compass", "truth", "none"});
  params.heading_source = heading_policy_from_string(heading_source);
  section.read("motion_components", params.motion_components);
  check_loaded(section.source_name(), [&] { params.check(); });
}

void ExplorationParams::check() const {
  if (new_place_dissimilarity) {
    check_range("exploration.new_place_dissimilarity", *new_place_dissimilarity, 0.0, 1000.0);
  }
  check_range("exploration.new_place_plateau_share", new_place_plateau_share, 0.01, 1.0);
  check_range("exploration.every_n_frames", every_n_frames, 0, 1000000);
  check_range("exploration.every_m", every_m, 0.0, 1000.0);
  check_range("exploration.thumbnail_width_px", thumbnail_width_px, 8, 4096);
  check_range("exploration.motion_components", motion_components, 0, 4096);
}

namespace {

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

}  // namespace

Explorer::Explorer(VisualMemory& memory, ExplorationParams params, std::string input,
                   std::string description, FrameOrder order)
    : memory_(memory),
      params_(std::move(params)),
      extractor_(memory.parameters().signature),
      order_(order) {
  params_.check();
  Run run;
  run.id = 0;
  for (const Run& r : memory_.runs()) run.id = std::max(run.id, r.id + 1);
  run.input = std::move(input);
  run.description = std::move(description);
  run.started_utc = utc_now();
  // Auto is settled by the first frame (track_heading); until then a stream's choice.
  switch (params_.heading_source) {
    case HeadingPolicy::kCompass:
      heading_source_ = HeadingSource::kCompass;
      break;
    case HeadingPolicy::kTruth:
      heading_source_ = HeadingSource::kTruth;
      break;
    case HeadingPolicy::kNone:
      heading_source_ = HeadingSource::kNone;
      break;
    case HeadingPolicy::kAuto:
      break;
  }
  run.heading_source = heading_source_.value_or(HeadingSource::kCompass);
  places_before_run_ = memory_.place_count();
  run_index_ = memory_.add_run(std::move(run));
  if (!params_.new_place_dissimilarity) {
    plateau_ = std::make_unique<signature::PlateauEstimate>(memory_.parameters().weights);
    for (PlaceIndex i = 0; i < places_before_run_; ++i) plateau_->add(memory_.place(i).signature);
    plateau_from_map_ = places_before_run_ >= kAutoWarmupFrames;
  }
}

std::optional<double> Explorer::plateau_per_value() const {
  return plateau_ ? plateau_->per_value() : std::nullopt;
}

std::optional<double> Explorer::floor_per_value() const {
  return plateau_ ? plateau_->floor_per_value() : std::nullopt;
}

std::optional<double> Explorer::new_place_threshold() const {
  if (params_.new_place_dissimilarity) {
    if (*params_.new_place_dissimilarity > 0.0) return params_.new_place_dissimilarity;
    return std::nullopt;
  }
  const std::optional<double> plateau = plateau_->per_value();
  if (!plateau || (!plateau_from_map_ && plateau_->signatures_seen() < kAutoWarmupFrames)) {
    return std::nullopt;
  }
  if (threshold_within_floor()) return std::nullopt;
  return params_.new_place_plateau_share * *plateau;
}

bool Explorer::threshold_within_floor() const {
  // Places a share of the way to the plateau apart must differ by more than views from one
  // spot do: otherwise the plateau is the floor's noise, no evidence of travel (see the header).
  const std::optional<double> plateau = plateau_per_value();
  const std::optional<double> floor = floor_per_value();
  return plateau && floor && params_.new_place_plateau_share * *plateau <= *floor;
}

const Run& Explorer::run() const {
  return memory_.runs()[run_index_];
}

std::optional<PlaceIndex> Explorer::add(const io::Frame& frame) {
  if (frame.truth) check_pose(*frame.truth, frame.source);  // every source's, before any use
  if (frame.odometry) check_pose(*frame.odometry, frame.source);
  // The distance travelled as the input measures it: its poses, or its odometry.
  const std::optional<CameraPose>& travelled = params_.odometry ? frame.odometry : frame.truth;
  const double step_m = travelled_step_m(travelled, frame.source);
  const signature::Signature signature = extractor_.compute(frame.image, frame.source);
  track_heading(frame, signature);
  if (plateau_) {
    // Only a sampled frame's step counts for the floor: the compass is asked of those alone
    // (previous_panorama_ is kept for them).
    const cv::Mat panorama = at_compass_width(frame.image);
    plateau_->add_frame(signature, !previous_panorama_.empty() && is_turn_on_the_spot(panorama));
    previous_panorama_ = plateau_->will_sample() ? panorama : cv::Mat();
  }
  ++frames_;
  memory_.record_run_progress(run_index_, frames_, places_);
  ++frames_since_place_;
  metres_since_place_ += step_m;
  previous_pose_ = travelled;

  bool new_place = !last_place_;
  if (!new_place && params_.every_n_frames > 0 && frames_since_place_ >= params_.every_n_frames) {
    new_place = true;
  }
  // Travelled distance: a hair of slack so that a 0.3 m grid step counts as 0.3 m.
  if (!new_place && params_.every_m > 0.0 && travelled &&
      metres_since_place_ >= params_.every_m * (1.0 - 1e-9)) {
    new_place = true;
    // The map's scale, for the lattice (lattice/organise.hpp): consecutive places every_m apart.
    memory_.set_exploration_spacing_m(params_.every_m);
  }
  const std::optional<double> threshold = new_place ? std::nullopt : new_place_threshold();
  if (threshold) {
    const signature::Signature& last = memory_.place(*last_place_).signature;
    const double per_value =
        signature::dissimilarity(last, signature, -1, memory_.parameters().weights) /
        static_cast<double>(signature.size());
    new_place = per_value >= *threshold;
  }
  if (!new_place) return std::nullopt;
  return make_place(frame, signature);
}

double Explorer::travelled_step_m(const std::optional<CameraPose>& travelled,
                                  const std::string& source) const {
  if (!travelled || !previous_pose_) return 0.0;
  const double step_m =
      std::hypot(travelled->x_m - previous_pose_->x_m, travelled->y_m - previous_pose_->y_m);
  // Consecutive places are every_m apart by construction (the map's scale, lattice/organise.hpp).
  // A frame may come a spacing after the last (a robot that stops every spacing to take an
  // image, with its odometry's error); a step of more than two spacings passes a whole place
  // with no frame: a jump (an odometry reset, a gap in a bag) or frames too far apart.
  const double limit_m = 2.0 * params_.every_m;
  if (params_.every_m > 0.0 && step_m > limit_m) {
    std::ostringstream message;
    message << source << ": the " << (params_.odometry ? "odometry" : "poses") << " moved "
            << fixed(step_m, 2) << " m since the previous frame, more than two places' spacing ("
            << limit_m << " m, --every-m " << params_.every_m
            << "): a jump (an odometry reset, frames missing) or frames too far apart; explore "
               "the stretches either side of it as separate runs, or give a larger --every-m";
    throw InputError(message.str());
  }
  return step_m;
}

PlaceIndex Explorer::add_place(const io::Frame& frame) {
  if (frame.truth) check_pose(*frame.truth, frame.source);
  if (frame.odometry) check_pose(*frame.odometry, frame.source);
  const signature::Signature signature = extractor_.compute(frame.image, frame.source);
  track_heading(frame, signature);
  ++frames_;
  memory_.record_run_progress(run_index_, frames_, places_);
  previous_pose_ = params_.odometry ? frame.odometry : frame.truth;
  return make_place(frame, signature);
}

void Explorer::track_heading(const io::Frame& frame, const signature::Signature& signature) {
  if (!heading_source_) {
    heading_source_ = order_ == FrameOrder::kUnordered && frame.truth ? HeadingSource::kTruth
                                                                      : HeadingSource::kCompass;
    memory_.set_run_heading_source(run_index_, *heading_source_);
  }
  if (heading_source_ != HeadingSource::kCompass) return;
  const cv::Mat panorama = at_compass_width(frame.image);
  if (order_ == FrameOrder::kUnordered) {
    if (!place_matcher_) {
      place_matcher_ = std::make_unique<compass::PairMatcher>(params_.compass.matcher);
    }
    compass_heading_rad_ = run_place_panoramas_.empty()
                               ? initial_heading(frame, signature)
                               : heading_from_nearest_place(panorama, signature);
    run_place_panoramas_.push_back(panorama);
    return;
  }
  const compass::CompassFrame compass_frame(panorama, frame.index, frame.source);
  if (!compass_) {
    compass_ = std::make_unique<compass::VisualCompass>(params_.compass,
                                                        initial_heading(frame, signature));
  }
  compass_heading_rad_ = compass_->push(compass_frame).heading_rad;
}

cv::Mat Explorer::at_compass_width(const cv::Mat& panorama) const {
  if (params_.compass_width_px && *params_.compass_width_px != panorama.cols) {
    return compass::resample_columns(panorama, *params_.compass_width_px);
  }
  return panorama;
}

bool Explorer::is_turn_on_the_spot(const cv::Mat& panorama) {
  // A turn leaves, after the compass's best rotation (sub-pixel), at most what rolling the
  // image by half a column does: the rotation lies within half a column of a whole shift, and
  // the distance grows about linearly with a small roll (PairMatch::self_step, one column's).
  // More is parallax or a changed scene: the frames are not of one spot.
  if (!step_matcher_)
    step_matcher_ = std::make_unique<compass::PairMatcher>(params_.compass.matcher);
  const compass::PairMatch match = step_matcher_->match(compass::CompassFrame(previous_panorama_),
                                                        compass::CompassFrame(panorama));
  return match.distance_min <= 0.5 * match.self_step;
}

double Explorer::heading_from_nearest_place(const cv::Mat& panorama,
                                            const signature::Signature& signature) const {
  // (Averaging the readings through the 3-6 most similar places instead was no better: the
  // errors are biases shared by neighbours, not noise.) Every place of this run so far has a
  // heading: each got one here.
  const PlaceIndex nearest = *most_similar_place(signature, places_before_run_,
                                                 places_before_run_ + run_place_panoramas_.size());
  const Place& place = memory_.place(nearest);
  const double turn_rad = signature::relative_heading(place.signature, signature).turn_rad;
  // The step's direction seen from the second image, brought to its front (see the header).
  const signature::MotionEstimate motion = signature::estimate_motion(place.signature, signature);
  const int width = panorama.cols;
  const int roll_px = motion.valid ? static_cast<int>(std::lround(shift_px_of_rotation(
                                         motion.bearing_rad - turn_rad, width)))
                                   : 0;
  const compass::CompassFrame first(
      roll_columns(run_place_panoramas_[nearest - places_before_run_], roll_px));
  const compass::CompassFrame second(roll_columns(panorama, roll_px));
  const compass::PairMatch match = place_matcher_->match(
      first, second, static_cast<int>(std::lround(-shift_px_of_rotation(turn_rad, width))));
  return *place.heading_rad + match.rotation_rad;
}

double Explorer::initial_heading(const io::Frame& frame,
                                 const signature::Signature& signature) const {
  const std::optional<PlaceIndex> nearest = most_similar_place(signature, 0, places_before_run_);
  if (nearest) {
    const Place& place = memory_.place(*nearest);
    return wrap_angle(*place.heading_rad +
                      signature::relative_heading(place.signature, signature).turn_rad);
  }
  return frame.truth ? frame.truth->heading_rad : 0.0;
}

std::optional<PlaceIndex> Explorer::most_similar_place(const signature::Signature& signature,
                                                       PlaceIndex begin, PlaceIndex end) const {
  // By the full-signature dissimilarity, a linear scan: once per run for the gauge, once per
  // image of a grid database (O(n^2) over n images, seconds for thousands, next to reading
  // them).
  std::optional<PlaceIndex> nearest;
  double nearest_dissimilarity = 0.0;
  for (PlaceIndex i = begin; i < end; ++i) {
    const Place& place = memory_.place(i);
    if (!place.heading_rad) continue;
    const double d =
        signature::dissimilarity(place.signature, signature, -1, memory_.parameters().weights);
    if (!nearest || d < nearest_dissimilarity) {
      nearest = i;
      nearest_dissimilarity = d;
    }
  }
  return nearest;
}

PlaceIndex Explorer::make_place(const io::Frame& frame, const signature::Signature& signature) {
  Place place;
  place.signature = signature;
  place.source = frame.source;
  place.frame_index = frame.index;
  place.run = run().id;
  place.time_s = frame.time_s;
  place.truth = frame.truth;
  if (params_.odometry) place.odometry = frame.odometry;
  if (heading_source_ == HeadingSource::kTruth && !frame.truth) {
    throw UsageError(frame.source + ": headings come from the input's poses (heading_source " +
                     to_string(params_.heading_source) + ") but this frame has none");
  }
  if (heading_source_ == HeadingSource::kTruth) {
    place.heading_rad = frame.truth->heading_rad;
    place.heading_source = HeadingSource::kTruth;
  } else if (heading_source_ == HeadingSource::kCompass) {
    place.heading_rad = wrap_angle(compass_heading_rad_);
    place.heading_source = HeadingSource::kCompass;
  }
  if (params_.thumbnail_width_px > 0) {
    place.thumbnail_png = make_thumbnail(frame.image, params_.thumbnail_width_px);
  }
  const PlaceIndex index = memory_.add_place(std::move(place));

  if (last_place_) {
    const signature::Signature& from = memory_.place(*last_place_).signature;
    const signature::Signature& to = memory_.place(index).signature;
    Edge edge;
    edge.kind = order_ == FrameOrder::kUnordered ? EdgeKind::kListed : EdgeKind::kSequence;
    edge.dissimilarity = signature::dissimilarity(from, to, -1, memory_.parameters().weights);
    const signature::PhaseHeading heading = signature::relative_heading(from, to);
    edge.relative_heading_rad = heading.turn_rad;
    edge.heading_confidence = heading.confidence;
    const int motion_m = params_.motion_components > 0
                             ? std::min(params_.motion_components, from.components)
                             : from.components;
    if (motion_m >= 2) {
      const signature::MotionEstimate motion = signature::estimate_motion(from, to, motion_m);
      if (motion.valid) edge.motion_bearing_rad = motion.bearing_rad;
      edge.motion_bearing_stddev_rad = motion.bearing_stddev_rad;
      edge.parallax_rad = motion.parallax_rad;
    }
    memory_.add_edge(*last_place_, index, edge);
  }
  last_place_ = index;
  frames_since_place_ = 0;
  metres_since_place_ = 0.0;
  memory_.record_run_progress(run_index_, frames_, ++places_);
  return index;
}

Run explore_frames(VisualMemory& memory, const ExplorationParams& params,
                   const ExplorationInput& input) {
  const bool every_frame = input.all_frames || input.is_grid;
  std::ostringstream description;
  description << "omninav explore --input " << input.name << "; ";
  if (every_frame) {
    description << "every frame a place";
  } else {
    description << "new_place_dissimilarity ";
    if (params.new_place_dissimilarity) {
      description << *params.new_place_dissimilarity;
    } else {
      description << "auto (" << params.new_place_plateau_share << " of the plateau)";
    }
    description << ", every_n_frames " << params.every_n_frames << ", every_m " << params.every_m;
    if (params.odometry) description << " (by odometry)";
  }
  description << ", heading_source " << to_string(params.heading_source);
  Explorer explorer(memory, params, input.name, description.str(),
                    input.is_grid ? FrameOrder::kUnordered : FrameOrder::kStream);
  Progress progress("explore", input.frame_count);
  while (std::optional<io::Frame> frame = input.next()) {
    if (!every_frame && params.every_m > 0.0 && !frame->truth) {
      // A distance travelled needs poses: without them every_m would do nothing.
      std::ostringstream message;
      message << frame->source << ": no pose, and a place every " << params.every_m
              << " m (--every-m, memory.yaml exploration.every_m) needs the input's poses; give "
                 "--every-n-frames or --dissimilarity instead";
      throw UsageError(message.str());
    }
    if (!every_frame && params.odometry && !frame->odometry) {
      throw UsageError(
          frame->source +
          ": no odometry, which --odometry needs (a BoB database's 'Odometry X [mm]', "
          "'Odometry Y [mm]', 'Odometry Heading [degrees]' columns, a CSV's "
          "odometry_x_m, odometry_y_m, odometry_heading_deg, or a bag's --pose-topic)");
    }
    if (every_frame) {
      explorer.add_place(*frame);
    } else {
      explorer.add(*frame);
    }
    progress.advance();
  }
  if (explorer.frames_seen() == 0) throw InputError(input.name + ": no frames");
  if (!every_frame && explorer.plateau_per_value()) {
    std::ostringstream note;
    note << "plateau " << fixed(*explorer.plateau_per_value(), 3) << " per value, threshold "
         << fixed(params.new_place_plateau_share * *explorer.plateau_per_value(), 3)
         << " at the end";
    if (explorer.threshold_within_floor()) {
      note << ", within the floor between frames (" << fixed(*explorer.floor_per_value(), 3)
           << "): no travel seen, no places by dissimilarity";
    }
    memory.add_run_note(memory.runs().size() - 1, note.str());
    log_info("explore: " + note.str());
  }
  if (input.is_grid && input.grid_spacing_m) memory.set_grid_spacing_m(*input.grid_spacing_m);
  return explorer.run();
}

}  // namespace omninav::memory
