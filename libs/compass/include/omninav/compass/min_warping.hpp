#pragma once
// Min-warping (Möller 2009; Möller, Krzykawski & Gerstmayr 2010): the direction of travel α and
// the rotation ψ between two panoramas, estimated together by a search over (α, ψ) in which
// every column of the first panorama finds its own best partner in the second.
//
// GEOMETRY (Möller 2009; docs/compass.md "Min-warping"). The first panorama (the snapshot,
// Möller's S) is taken at place A, the second (the current view, C) at place B. In A's frame
// the robot travelled a distance d towards azimuth α and turned counter-clockwise by ψ. A point
// at azimuth x and distance r from A is seen from B at azimuth x' and distance r'. With
// u = x − α and v = x' + ψ − α (the angles from the direction of travel) and ν = d/r:
//     v = atan2(sin u, cos u − ν)                       the point moves away from the focus of
//                                                       expansion as ν grows (ν = 0: at infinity)
//     σ = r/r' = 1 / sqrt(1 − 2ν·cos u + ν²)            the column's vertical scale
// The equal-distance assumption applies within a column: every point of a column is taken to
// be at the same distance, so the whole column scales by σ (Möller 2009). Distances
// differ from column to column: each column of the snapshot takes the minimum over ν of its
// column distance ("min"-warping), and the (α, ψ) with the smallest sum of those minima wins.
//
// SCALE PLANES on omninav's rows (linear in elevation, camera.yaml). A point at height h seen at
// elevation e from A is seen at e' from B with tan e' = σ·tan e. The scale plane of σ > 1
// compares the current column with the snapshot column magnified about the horizon: the
// magnified column's row at elevation e' takes the snapshot's value at elevation
// atan(tan e' / σ), interpolated linearly between rows (an exact map on equiangular rows, not
// the linear magnification of rows that images with rows linear in tan e would allow). For
// σ < 1 the current column is magnified by 1/σ instead, so that a column is only ever
// magnified, never shrunk (no aliasing). The stack holds `scale_planes` values of σ, spaced
// evenly in log σ over [1/max_scale, max_scale] (1 included); a column pair takes the plane
// nearest its σ, the end planes beyond them.
//
// COLUMN DISTANCE: the normalised sum of squared differences of the zero-mean columns (our
// reading of the papers' normalised measures; docs/compass.md "Readings and choices"):
//     d(x, y) = Σ (x − x̄ − y + ȳ)² / (Σ (x − x̄)² + Σ (y − ȳ)²)  ∈ [0, 2]
// 1 for unrelated columns, 0 for equal ones; 1 when both are constant (no evidence either way).
// The images are matched in grey (the channels' mean), as the papers' were.
//
// SEARCH RANGE (Möller, Krzykawski & Gerstmayr 2010, "search range"): ν ≤ max_relative_distance
// (< 1: no point nearer to A than the distance travelled), which bounds how far a column may
// move from its pure-rotation position.
//
// RESOLUTION. The search runs on the panoramas reduced to search_width_px × search_height_px by
// area averaging; α and ψ step by 360°/search_width_px; the minimum is refined by a parabola
// through its neighbours along each axis.
//
// Two implementations: MinWarping (fast: the column distances of every scale plane computed at
// once per pair as one matrix product per plane, then the search is table lookups and vector
// minima over all ψ at once) and min_warping_reference (exhaustive loops written from the
// equations, sharing no code with the fast one: the test oracle).

#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "omninav/core/panorama.hpp"

namespace omninav::compass {

struct MinWarpingParams {
  // Columns of the search: α and ψ step by 360°/search_width_px (4° at 90). The panoramas are
  // reduced to it by area averaging (whole blocks when their width is a multiple). Ours: the
  // resolution at which the search meets the robot's speed target (tests/bench).
  int search_width_px = 90;
  // Rows of the search (the panoramas' rows are averaged, or interpolated when fewer).
  int search_height_px = 45;
  // ν_max = d/r, the search range (Möller, Krzykawski & Gerstmayr 2010): every point is taken
  // to be farther than d / ν_max from the first place. 0.05..0.99.
  double max_relative_distance = 0.95;
  // The stack of scale planes: σ in [1/max_scale, max_scale], evenly in log σ (1.0..4.0).
  double max_scale = 2.0;
  int scale_planes = 9;  // odd, so that σ = 1 is a plane (3..33)
  // ν samples per snapshot column when the candidate partners (column offset, scale plane) are
  // enumerated, evenly in [0, ν_max] (16..4096); dense enough that no column offset is skipped.
  int distance_samples = 256;
  // A panorama whose zero-mean columns differ from those a quarter turn away by less than
  // this RMS (grey levels) is featureless: nothing to match (a constant or horizontally uniform
  // image). One grey level: what 8-bit quantisation and sensor noise alone leave.
  double featureless_below_grey = 1.0;

  // Throws UsageError naming the parameter when a value is out of range.
  void check() const;
};

struct MinWarpingResult {
  // ψ: the counter-clockwise turn from the first panorama's heading to the second's.
  double rotation_rad = 0.0;
  // α: the direction from the first place to the second, in the first panorama's frame (an
  // azimuth relative to its front, counter-clockwise positive; add its heading for the world).
  double travel_rad = 0.0;
  // The direction from the second place back to the first, in the second panorama's frame
  // (Möller's home vector when the first panorama is the snapshot): α + π − ψ, wrapped.
  double home_rad = 0.0;
  // Mean column distance at the minimum (0..2), and that of the best pure rotation (every
  // column at its rotated position, σ = 1): the joint estimate explains the pair better than a
  // turn alone by their difference.
  double cost = 0.0;
  double rotation_only_cost = 0.0;
  double rotation_only_rad = 0.0;  // the best pure rotation's ψ (whole search steps)
  int travel_index = 0;            // the grid minimum, search columns
  int rotation_index = 0;
  // Either panorama is featureless (MinWarpingParams::featureless_below_grey): no estimate;
  // the angles are 0.
  bool featureless = false;

  // The direction from the first place to the second in the world, given the first
  // panorama's heading (counter-clockwise from +x): the home vector's world direction, reversed.
  double travel_world_rad(double first_heading_rad) const;
};

// One panorama reduced and magnified for the search: made once, matched against any number of
// others (a query against every place of a map).
class MinWarpingView {
 public:
  MinWarpingView();
  ~MinWarpingView();
  MinWarpingView(MinWarpingView&&) noexcept;
  MinWarpingView& operator=(MinWarpingView&&) noexcept;
  const std::string& name() const;
  bool featureless() const;
  cv::Size size() const;  // the panorama's, before it was reduced for the search

  struct Data;
  const Data& data() const { return *data_; }

 private:
  friend class MinWarping;
  std::unique_ptr<Data> data_;
};

class MinWarping {
 public:
  // `geometry` gives the elevations of the panoramas' rows (camera.yaml's panorama section);
  // its width and height are not used (the images say theirs). Throws UsageError for bad
  // parameters.
  MinWarping(const MinWarpingParams& params, const PanoramaGeometry& geometry);
  ~MinWarping();
  MinWarping(const MinWarping&) = delete;
  MinWarping& operator=(const MinWarping&) = delete;

  // Accepts 8-bit or 32-bit float panoramas, 1 or 3 channels, at least search_width_px wide.
  // Throws InputError naming `name` when the image is empty, of another type, narrower than the
  // search, or has non-finite pixels.
  MinWarpingView prepare(const cv::Mat& panorama, const std::string& name) const;

  // Throws InputError naming both when their sizes differ.
  MinWarpingResult estimate(const MinWarpingView& first, const MinWarpingView& second) const;
  MinWarpingResult estimate(const cv::Mat& first, const cv::Mat& second) const;
  // `second` (named `name`) brought to the size of the panorama `first` was prepared from, by
  // area averaging, then matched: a view of another camera's resolution against a stored
  // snapshot (a place's thumbnail, a goal image). Throws what prepare() throws.
  MinWarpingResult estimate_resized(const MinWarpingView& first, const cv::Mat& second,
                                    const std::string& name) const;

  // The best pure rotation alone (every column at its rotated position, σ = 1), as estimate()
  // reports it beside the joint minimum, at a small part of its cost (one matrix product): how
  // alike two panoramas are whatever their turn. Throws InputError naming both when their sizes
  // differ.
  struct RotationOnly {
    double cost = 1.0;          // mean column distance (0..2); 1 for featureless panoramas
    double rotation_rad = 0.0;  // whole search steps
  };
  RotationOnly rotation_only(const MinWarpingView& first, const MinWarpingView& second) const;

  // The mean column distance at every grid point, rows α (search columns of the first
  // panorama), columns ψ (search columns), CV_64F; for tests and figures.
  cv::Mat cost_surface(const MinWarpingView& first, const MinWarpingView& second) const;

  const MinWarpingParams& params() const { return params_; }

 private:
  struct Impl;
  MinWarpingParams params_;
  std::unique_ptr<Impl> impl_;
};

// The exhaustive reference: for every grid (α, ψ) and snapshot column, every sampled ν, the
// column distance computed from the pixels. Same parameters, same result up to rounding; slow
// (tests use small search widths). The panoramas' width and height must be multiples of the
// search's (it averages whole blocks only). `cost_surface`, when given, receives the surface as
// MinWarping::cost_surface does.
MinWarpingResult min_warping_reference(const cv::Mat& first, const cv::Mat& second,
                                       const MinWarpingParams& params,
                                       const PanoramaGeometry& geometry,
                                       cv::Mat* cost_surface = nullptr);

}  // namespace omninav::compass
