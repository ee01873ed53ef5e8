#pragma once
// The memory graph the plan and the belief run over: links between places that the map itself
// confirms, never a pair that merely looks alike. Four kinds:
//   - travelled: consecutive places of a stream (the robot drove from one to the next; a
//     travelled link is never dropped). Its length is the distance the input's poses or odometry
//     put between the two places when the exploration recorded it (explore --every-m), else the
//     map's spacing; its direction is the direction of motion from the phases (Menegatti et al.
//     2004, §3.4: signature/motion.hpp), fitted from both ends with the turn held at the
//     headings' difference (the compass's).
//   - grid: places of a grid database (whose images carry the database's own positions and
//     headings, heading_source "truth") within one grid step of each other, 8-neighbourhood,
//     whose images agree: a pair whose dissimilarity is far above the map's typical grid step
//     stands either side of a wall or furniture, and is left out. Direction and length from
//     the database's positions.
//   - revisit: a place of a stream seen again later in the stream (a loop closure, a lane driven
//     beside an earlier one), accepted only when a run of consecutive views matches a run of
//     consecutive places (sequence matching, Milford & Wyeth 2012, SeqSLAM: forwards or
//     backwards along the earlier stretch) about as well as consecutive places match each
//     other, and the motion fitted between the two places agrees from both ends. Direction from
//     that fit, length one spacing (the pose graph of a map made by driving measures it from the
//     fit's parallax, MeasuredLink::parallax_rad). The runs compared are those of each view's
//     most similar places (an index, similar_places.hpp), not of every place: Fast-SeqSLAM's
//     candidates (Siam & Zhang 2017), so the search grows with the places, not with their pairs.
//   - neighbour: places that the organised lattice of a map made by driving with odometry (the
//     robust pose graph of travelled links and confirmed revisits, docs/lattice.md) puts beside
//     each other, whose images agree. Lanes driven side by side pass each other at a spacing;
//     a revisit joins a pair of them here and there, and a route between two places a lane
//     apart went round by the lanes' ends (7 times the straight line at the 90th percentile of
//     the evaluation suite's driven maps). Given by lattice_neighbour_links once the map is
//     organised; a look-alike cannot make one, since the lattice places what the robot drove.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "omninav/lattice/similar_places.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::lattice {

// Why a link of the memory graph is trusted.
enum class LinkKind {
  kTravelled,  // the robot drove from one place to the other while exploring
  kGrid,       // neighbours of a grid database whose images agree
  kRevisit,    // a stretch seen again, confirmed by a run of matching views
  kNeighbour,  // beside each other in a driven map's organised lattice, images agreeing
};

// A link of the memory graph: its length and its direction at either end, relative to that
// place's stored heading.
struct MeasuredLink {
  std::pair<int, int> places;            // (a, b)
  double length_m = 0.0;                 // what the link adds to a route
  double direction_at_first_rad = 0.0;   // from a towards b, relative to a's stored heading
  double direction_at_second_rad = 0.0;  // from b towards a, relative to b's stored heading
  LinkKind kind = LinkKind::kTravelled;
  // A revisit's parallax: the baseline over the depth of the scene, ρ = d / r, of the motion
  // fitted between its places (TwoWayFit, the two ways' mean); 0 for the other kinds.
  double parallax_rad = 0.0;
  // ... and that fit's residual (TwoWayFit::residual, the worse of the two ways'), at the turn
  // the stored headings give; 0 for the other kinds.
  double fit_residual = 0.0;
};

struct LinkParams {
  // A grid link is kept when its images' mean dissimilarity per value is at most this many
  // times the median over the map's grid links: chosen across the zoo (lattice.yaml). A
  // lattice neighbour link, when at most this many times the median over the travelled links:
  // the same claim, that a pair far less alike stands either side of a wall.
  double grid_agreement_ratio = 2.0;
  // ... and when the direction of motion the phases fit from either end lies within this many
  // degrees of the database's.
  double grid_direction_deg = 45.0;
  // Sequence matching: views in a run (odd; the place and (run − 1) / 2 either side).
  int revisit_run = 5;
  // A revisit's run must match within this many times the median dissimilarity per value of the
  // map's travelled links (places one spacing apart).
  double revisit_ratio = 1.25;
  // A revisit's two places' thumbnails, at their best pure rotation, must be as alike as this
  // many times the median of the travelled links' (image_agreement.hpp): a place seen again
  // looks like it did, where a look-alike differs in the detail the signature drops. Chosen
  // across the zoo leaving one family out (lattice.yaml).
  double revisit_image_ratio = 1.15;
  // Without thumbnails: the two fits of a revisit's motion (from each end) must agree within
  // this (degrees).
  double revisit_disagreement_deg = 20.0;
  // At most this many revisits per place (its best runs).
  int revisits_per_place = 2;
  // The runs compared with a place's: those at its most similar places, this many (chosen
  // across the zoo: more candidates let more look-alikes' runs in).
  int revisit_candidates = 3;
  // The odometry's relative standard deviation of a step's distance and turn. Two places of one
  // stream are a revisit only when their odometry puts them within 1.5 spacings plus three
  // standard deviations of its drift over the way between them (odometry_spread.hpp): a turn's
  // error swings all that follows, so the drift grows with the turns as well as the distance.
  double odometry_noise = 0.05;
  // Lattice neighbours lie within this many of the lattice's spacings (the median length of its
  // travelled links) of each other. Chosen across the zoo leaving one family out (lattice.yaml):
  // the nearer pairs, the surer (on the suite's driven maps 87-100 % of the pairs within one
  // spacing are truly within 1.5, against 73-99 % within 1.5).
  double neighbour_spacings = 1.0;

  // The ranges of navigation.yaml's links section. Throws UsageError naming the key
  // (core/param_check.hpp); the loader and confirmed_links call it.
  void check() const;
};

// Reads the `links:` section of lattice.yaml.
void load_link_params(const ConfigReader& section, LinkParams& params);

// The confirmed links of `memory`, given each place's heading in one frame (lattice_headings)
// and the distance between consecutive places. Logs how many of each kind. Empty for a map
// without any (one place, or an unordered input without positions): the caller says so.
std::vector<MeasuredLink> confirmed_links(const memory::VisualMemory& memory,
                                          const std::vector<double>& headings_rad, double spacing_m,
                                          const LinkParams& params);

// The same, with the places' dissimilarities and each place's most similar places (at least
// params.revisit_candidates of them, most similar first) already searched: organise shares
// them with the springs.
std::vector<MeasuredLink> confirmed_links(
    const memory::VisualMemory& memory, const std::vector<double>& headings_rad, double spacing_m,
    const LinkParams& params, const PlaceDissimilarities& dissimilarity,
    const std::vector<std::vector<SimilarPlace>>& most_similar);

// The links between the places that `positions` (the map's organised lattice, one per place)
// puts within params.neighbour_spacings of each other and that `links` does not join already,
// whose mean dissimilarity per value is at most params.grid_agreement_ratio times the median
// of the travelled links'. Each direction is the lattice's, turned into the place's own frame by
// the turn between its travelled links' directions in the lattice and as stored (their
// odometry's), so a compass's drift does not enter; the length is the lattice's, in the
// travelled links' metres. Empty unless the map was made by driving with odometry (its lattice
// is then a pose graph of what the robot drove; a spring model's, from appearance alone, can
// put look-alikes side by side). Logs how many. Throws UsageError when `positions` is not one
// per place.
std::vector<MeasuredLink> lattice_neighbour_links(const memory::VisualMemory& memory,
                                                  const std::vector<Eigen::Vector2d>& positions,
                                                  const std::vector<MeasuredLink>& links,
                                                  const LinkParams& params);

// Eq. 6 between places a and b of `memory`, per compared value (the map's weights).
double dissimilarity_per_value(const memory::VisualMemory& memory, int a, int b);

// The median over `links` of their places' mean dissimilarity per value (Eq. 6, the map's
// weights): what one link's length costs in appearance. None without links.
std::optional<double> median_dissimilarity_per_value(const memory::VisualMemory& memory,
                                                     const std::vector<MeasuredLink>& links);

// "travelled", "grid", "revisit", "neighbour".
std::string to_string(LinkKind kind);

}  // namespace omninav::lattice
