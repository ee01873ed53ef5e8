#pragma once
// Organising a visual memory into a lattice. Two inputs, two methods:
//   - a map made by driving with odometry (travelled links between places that kept the
//     robot's odometry) is a robust pose graph over its confirmed links (confirmed_links.hpp,
//     pose_graph.hpp): the robot's path by its odometry and revisits confirmed by sequence
//     matching, each of which the solver may switch off, with §3.2's springs as weak
//     constraints beside them;
//   - any other map (a grid database, an unordered folder, a stream without odometry) is the
//     spring model of
//     Menegatti et al. 2004, §3: distances estimated from similarity (calibrated without ground
//     truth), springs between places, motion directions from the phases (spring_lattice.hpp).
// Either way the positions are written into the places.

#include <optional>
#include <string>

#include "omninav/lattice/confirmed_links.hpp"
#include "omninav/lattice/pose_graph.hpp"
#include "omninav/lattice/spring_lattice.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::lattice {

// How the links of a map made by driving become the pose graph's measurements.
struct DrivenLatticeParams {
  // The odometry's relative standard deviation over a step, of its distance and of its turn.
  // Larger than a robot's per-step noise (Menegatti et al. 2004, §3.4, know the distance
  // "within 10 %"): each step is taken as independent, where wheel slip persists over many.
  // Chosen across the zoo, leaving one family out (docs/evaluation.md).
  double odometry_noise = 0.3;
  // Standard deviation of a turn measured from the images, degrees: the compass's between
  // consecutive places without odometry, the phases' (Eq. 1) between a revisit's two places.
  double visual_turn_stddev_deg = 5.0;
  PoseGraphParams solver;
};

struct OrganiseParams {
  // The scale: the distance between consecutive places of the exploration, metres. 0: take it
  // from the map (the exploration's spacing, VisualMemory::exploration_spacing_m); a value
  // given here (by the user) wins over the map's.
  double step_m = 0.0;
  int neighbours = 8;           // springs per place: its most similar places
  double range_fraction = 0.4;  // x₁ where dissimilarity reaches this share of its plateau
  // Springs longer than this many steps only push (SpringMeasurement::at_least): measured on
  // rendered grids, the calibrated distance follows the truth up to about one step and then
  // saturates (pairs 0.6 m apart read 0.43-0.47 m, pairs 3 m apart 0.45-0.60 m).
  double at_least_beyond_steps = 1.2;
  bool motion_constraints = true;  // motions measured from the phases (§3.4)
  int motion_neighbours = 3;       // motions to each place's most similar places, besides the
                                   // consecutive ones
  double step_likeness = 1.5;      // consecutive images of an unordered input (a grid
                                   // database) are one step apart when their calibrated
                                   // distance is at most this many steps (a stream's always are)
  // A stream's steps point where the robot was heading (the mean of the two places' headings,
  // plus the camera's offset from the way it drives, measured over the steps) instead of where
  // the phases' fit says: a robot drives forward, and in clutter or near the ground the fit of
  // a 30 cm step is often tens of degrees off (docs/lattice.md).
  bool steps_along_heading = true;
  // Headings from the visual compass are re-solved for the motions from the compass's turns
  // between consecutive places and the phases' turns between each place and its most similar
  // places (src/headings.hpp): the compass jumps where a robot turns on the spot.
  bool synchronise_compass_headings = true;
  // A neighbour motion whose fit leaves more than this many times the map's median residual
  // is a look-alike's and is dropped (motions.hpp).
  double look_alike_residual = 1.5;
  // A neighbour motion between places of a stream at most this many steps apart that disagrees
  // with the steps between them by more than step_check_sigmas standard deviations (of the
  // steps' dead reckoning over that many steps) is dropped too (0: never).
  int step_check_steps = 10;
  double step_check_sigmas = 3.0;
  double motion_direction_stddev_deg = 11.5;  // of a motion's measured direction
  double motion_length_stddev = 0.3;          // of a motion's length, as a share of it
  // The same for motions to most similar places, whose length is the calibrated distance: it
  // saturates beyond about one step (two steps read as 1.4-1.6), so their direction is what
  // they contribute and their length is held loosely.
  double neighbour_motion_length_stddev = 1.0;
  LatticeParams lattice;       // correlation_range_m is set by the calibration
  LinkParams links;            // a map made by driving: its confirmed links ...
  DrivenLatticeParams driven;  // ... as the pose graph's measurements
  // The verdict of the lattice quality (LatticeQuality, measured without ground truth): the
  // lattice is not trustworthy when more than this share of its motions point more than 45°
  // away from where the lattice puts their places, or when the motions that survived the
  // look-alike checks left the places in more than one piece (joined by look-alikes only).
  double max_motions_off = 0.02;

  // The ranges of lattice.yaml's organise section (the lattice's keys too). Throws UsageError
  // naming the key (core/param_check.hpp); the loader and organise() call it.
  void check() const;
};

// Reads the `organise:` section of lattice.yaml, then checks it (OrganiseParams::check).
void load_organise_params(const ConfigReader& section, OrganiseParams& params);

// Reads the `driven:` section of lattice.yaml (checked with the rest by OrganiseParams::check).
void load_driven_params(const ConfigReader& section, DrivenLatticeParams& params);

// How dissimilarity maps to distance, calibrated on the map itself (our reading of Fig. 7 and
// §3.2, which show the curve but give no formula). Fig. 7 is linear at short range; its slope,
// though, depends on the place: parallax is inversely proportional to depth, so views change
// faster near walls and furniture than in the open. Each place's most similar other place is
// taken to be one exploration step away (true of the spacing policies: a place every step), so
// that place a's local step dissimilarity is s_a, its dissimilarity to that place, and
//     x(a, b) = step · D(a, b) / √(s_a · s_b).
// Beyond a short range D saturates (the plateau: the 90th percentile of all pairs) and says
// little; x₁ of Eq. 5, where stiffness falls to 0.1, is where the median step's line reaches
// range_fraction of the plateau.
// Where the scale came from: the user (OrganiseParams::step_m), the map's exploration spacing
// (VisualMemory::exploration_spacing_m) or the grid spacing its grid database stated
// (VisualMemory::grid_spacing_m), in that order.
enum class ScaleSource { kUser, kMap, kGrid };
// "user", "map: exploration.every_m" or "map: the grid database's grid.separationMM".
std::string to_string(ScaleSource source);

struct DistanceCalibration {
  double step_m = 0.0;  // the scale used
  ScaleSource step_source = ScaleSource::kUser;
  double step_dissimilarity = 0.0;     // the median of the places' local step dissimilarity
  double plateau_dissimilarity = 0.0;  // the 90th percentile of all pairs' dissimilarity
  double correlation_range_m = 0.0;    // x₁
  std::vector<double> local_step_dissimilarity;  // s_a, one per place

  double distance_m(int a, int b, double dissimilarity) const;
};

struct OrganiseResult {
  DistanceCalibration calibration;
  std::vector<SpringMeasurement> springs;  // every spring offered to the solver
  std::vector<MotionMeasurement> motions;
  int look_alikes_dropped = 0;  // neighbour motions dropped as look-alikes (src/motions.hpp)
  int motion_joins = 0;         // motions added to join places the others left apart
  LatticeResult lattice;
  // A map made by driving: its links, and how many revisits the pose graph switched off (its
  // switch below 0.5: the rest of the graph disagrees with them).
  int travelled_links = 0;
  int revisits = 0;
  int revisits_switched_off = 0;
  memory::LatticeQuality quality;  // also stored in the map (VisualMemory::lattice_quality)
};

// The lattice against the motions it was solved from, without ground truth: each motion's
// measured displacement (direction, length) against the lattice's, over every motion but those
// added to join pieces; the verdict from `max_motions_off` and the pieces.
memory::LatticeQuality measure_quality(const std::vector<Eigen::Vector2d>& positions,
                                       const std::vector<MotionMeasurement>& motions, int joins,
                                       double step_m, double max_motions_off);

// Each place's heading in the lattice frame (the first place's heading along +x): stored
// headings when every place has one, else the relative headings measured between consecutive
// places (phases), integrated along the exploration; none for places that cannot be reached.
std::vector<std::optional<double>> lattice_headings(const memory::VisualMemory& memory);

// Calibrates and builds the springs. A map made by driving with odometry: its confirmed links
// and the springs (as weak constraints) solved as a pose graph; motions are then the links the
// pose graph kept, as displacements in the lattice frame (for the quality). Otherwise the
// spring model: the motions (src/motions.hpp: a stream's steps, a grid
// database's listed pairs that look one step apart, each place's most similar places but
// look-alikes, and what joins the rest), solves, and stores each place's lattice position
// (metres, lattice frame: place 0 at the origin, its heading along +x).
// Throws UsageError when the scale is unknown (no step given and none in the map) or the map
// has fewer than two places.
OrganiseResult organise(memory::VisualMemory& memory, const OrganiseParams& params);

}  // namespace omninav::lattice
