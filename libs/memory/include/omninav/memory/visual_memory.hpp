#pragma once
// The visual memory (Menegatti et al. 2004, §2-3): places, each a reference image reduced to
// its Fourier signature, and edges between places met one after the other. In memory it is a
// Boost.Graph adjacency_list whose vertex i is place i (places are only ever appended, so a
// place's index, its vertex and its id in the map file are one number). It is data only: the
// SQLite file that keeps it, and what of it is already on disk, are map_store.hpp's.

#include <Eigen/Core>
#include <boost/graph/adjacency_list.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "omninav/core/pose.hpp"
#include "omninav/signature/dissimilarity.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::memory {

// Where a place's heading came from. The map says so for every place, so that evaluation and
// later tools know whether headings are measured (compass), borrowed (truth) or absent.
enum class HeadingSource { kNone, kTruth, kCompass };

std::string to_string(HeadingSource source);
// "none", "truth" or "compass"; throws InputError otherwise.
HeadingSource heading_source_from_string(const std::string& text);

struct Place {
  signature::Signature signature;     // magnitudes and phases (§2.1)
  std::optional<double> heading_rad;  // the robot's heading at this place, REP 103
  HeadingSource heading_source = HeadingSource::kNone;
  std::vector<std::uint8_t> thumbnail_png;  // a small copy of the panorama, PNG-encoded
  std::string source;                       // the image file (or "video#frame n") it came from
  int frame_index = 0;                      // its index in that input sequence
  int run = 0;                              // the exploration run that added it (Run::id)
  std::optional<double> time_s;             // capture time, when the input knows it
  std::optional<CameraPose> truth;          // ground truth: for evaluation only, never used to map
  // Where the robot's own odometry put it (explore --odometry), in the odometry's frame: x, y
  // and heading (z, pitch and roll 0). Navigation measures the travelled links with it.
  std::optional<CameraPose> odometry;
  // Where the lattice (spring model, §3.2-3.4, libs/lattice) put the place: metres, in the
  // lattice's frame (place 0 at the origin, its heading along +x).
  std::optional<Eigen::Vector2d> lattice_position;
};

enum class EdgeKind {
  kSequence,  // the robot went from one place to the next during exploration (a stream)
  kListed,    // the next image of an unordered input (a grid database): listed after the
              // previous one, taken anywhere (a raster's row ends jump metres)
};
std::string to_string(EdgeKind kind);
EdgeKind edge_kind_from_string(const std::string& text);

struct Edge {
  EdgeKind kind = EdgeKind::kSequence;
  double dissimilarity = 0.0;         // Eq. 2/6 between the two places' signatures
  double relative_heading_rad = 0.0;  // heading(to) − heading(from) from the phases (Eq. 1)
  double heading_confidence = 0.0;    // signature::PhaseHeading::confidence
  // Direction of travel from `from` to `to` seen from `from`, counter-clockwise from its front
  // (§3.4, signature/motion.hpp); none when the translation was too small to measure.
  std::optional<double> motion_bearing_rad;
  double motion_bearing_stddev_rad = 0.0;
  double parallax_rad = 0.0;  // how far things abeam moved between the two views
};

// One `omninav explore` into the map.
struct Run {
  int id = 0;
  std::string input;        // what was explored (a folder, database, video)
  std::string started_utc;  // ISO 8601
  int frames = 0;           // frames read
  int places = 0;           // places added
  HeadingSource heading_source = HeadingSource::kNone;  // what the run's places used
  std::string description;                              // the command line or the caller's note
};

using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::bidirectionalS, Place, Edge>;
using PlaceIndex = std::size_t;

// The parameters every place of a map shares: its signatures must be comparable.
struct MapParameters {
  signature::SignatureParams signature;
  signature::ComponentWeights weights;  // α_k of Eq. 6, stored so queries use the same
  int panorama_rows = 0;                // rows of the panoramas (0: set by the first place)
};

// How far a lattice can be trusted, from the map alone: the motions measured between places
// (Menegatti et al. 2004, §3.4, the directions from the phases) against the lattice they were solved into.
struct LatticeQuality {
  int motions = 0;  // motions compared (steps, listed pairs and kept neighbour motions)
  // Median over the motions of |lattice displacement − measured motion| in steps.
  double motion_residual_steps = 0.0;
  // Share of the motions whose direction on the lattice is more than 45° off the measured one.
  double motions_off = 0.0;
  // Pieces the trusted motions left the places in, before look-alike pairs joined them: more
  // than one means the pieces' relative placement rests on look-alikes alone.
  int pieces = 1;
  bool trustworthy = true;  // the verdict (lattice/organise.hpp: thresholds)
};

class VisualMemory {
 public:
  explicit VisualMemory(MapParameters parameters = {});

  const MapParameters& parameters() const { return parameters_; }

  // The distance travelled between consecutive places when the exploration made a place every
  // so many metres (explore --every-m): the map's scale, which the lattice takes unless told
  // another. None when no run placed its places by distance.
  std::optional<double> exploration_spacing_m() const { return exploration_spacing_m_; }
  // Throws UsageError unless `metres` is finite and positive.
  void set_exploration_spacing_m(double metres);
  // The distance between neighbouring points of the grid a grid database states (BoB's
  // `grid.separationMM`), when a run explored one: the lattice's scale after every_m. Throws
  // UsageError unless `metres` is finite and positive.
  std::optional<double> grid_spacing_m() const { return grid_spacing_m_; }
  void set_grid_spacing_m(double metres);

  // How well the lattice agrees with the motions it was built from, measured without ground
  // truth (lattice/organise.hpp, LatticeQuality); none before the map is organised.
  const std::optional<LatticeQuality>& lattice_quality() const { return lattice_quality_; }
  void set_lattice_quality(const LatticeQuality& quality) { lattice_quality_ = quality; }

  std::size_t place_count() const { return boost::num_vertices(graph_); }
  std::size_t edge_count() const { return boost::num_edges(graph_); }
  // Throws UsageError for an index beyond the places.
  const Place& place(PlaceIndex index) const;

  // Appends a place; returns its index. Throws UsageError when its signature does not match
  // the map's (rows, colour, components).
  PlaceIndex add_place(Place place);
  void add_edge(PlaceIndex from, PlaceIndex to, const Edge& edge);

  const Graph& graph() const { return graph_; }

  // Edges in the order they were added: (from, to, properties).
  struct EdgeRef {
    PlaceIndex from;
    PlaceIndex to;
    const Edge* edge;
  };
  std::vector<EdgeRef> edges() const;

  // The lattice: one position per place (UsageError on another count), or none at all.
  void set_lattice_positions(const std::vector<Eigen::Vector2d>& lattice_positions);
  void clear_lattice_positions();

  // The explorations that made the map, in the order they ran.
  const std::vector<Run>& runs() const { return runs_; }
  // Appends a run; returns its index in runs().
  std::size_t add_run(Run run);
  // What a run has read and added so far, and where its places' headings came from. Throw
  // UsageError for an index beyond the runs.
  void record_run_progress(std::size_t run_index, int frames, int places);
  void set_run_heading_source(std::size_t run_index, HeadingSource source);
  // Appends "; <note>" to a run's description: what the input adds to it, e.g. a camera's frames
  // dropped or its stop by Ctrl-C. An empty note changes nothing.
  void add_run_note(std::size_t run_index, const std::string& note);

  // Whether every place has a ground-truth pose / a lattice position.
  bool all_have_truth() const;
  bool all_have_lattice() const;

  // Approximate bytes held (signatures, thumbnails, graph), for the benchmarks.
  std::size_t bytes() const;

 private:
  Run& run(std::size_t run_index);

  MapParameters parameters_;
  std::optional<double> exploration_spacing_m_;
  std::optional<double> grid_spacing_m_;
  std::optional<LatticeQuality> lattice_quality_;
  Graph graph_;
  // Edges in the order added, by position: the `out_position`-th out-edge of `from` (vecS
  // out-edge lists only grow at the end). Positions, unlike edge descriptors, survive copies.
  struct EdgeSlot {
    PlaceIndex from;
    std::size_t out_position;
  };
  std::vector<EdgeSlot> edge_order_;
  std::vector<Run> runs_;
};

}  // namespace omninav::memory
