#pragma once
// How alike two places' images are, whatever their turn: the best pure rotation of min-warping
// between their stored thumbnails (compass/min_warping.hpp: the mean over columns of the
// normalised distance of zero-mean columns, each column at its rotated position), over the
// median of the same between consecutive places of the streams (travelled links: one step
// apart, true by construction). A revisit is a place seen again, so its two images should be
// as alike as one step's; a look-alike's differ in the detail the Fourier magnitudes drop.

#include <optional>
#include <unordered_map>
#include <vector>

#include "omninav/compass/min_warping.hpp"
#include "omninav/lattice/confirmed_links.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav::lattice {

class ImageAgreement {
 public:
  // The unit from up to kSampledLinks of `travelled`, evenly spread. Unavailable when the map
  // keeps no thumbnails (or ones narrower than the search) or has no travelled links.
  ImageAgreement(const memory::VisualMemory& memory, const std::vector<MeasuredLink>& travelled);

  bool available() const { return unit_ > 0.0; }
  // The two places' distance over the unit; none when either lacks a usable thumbnail or is
  // featureless.
  std::optional<double> ratio(int a, int b);

 private:
  std::optional<double> distance(int a, int b);
  const compass::MinWarpingView* view(int place);

  const memory::VisualMemory& memory_;
  // The search's resolution decides the distance: min-warping's default search (90 x 45), the
  // same for every map and independent of compass.yaml, whose search serves the navigator. The
  // rows' elevations only shape the scale planes, which a pure rotation does not use.
  compass::MinWarping warping_{compass::MinWarpingParams{}, PanoramaGeometry{}};
  std::unordered_map<int, std::optional<compass::MinWarpingView>> views_;
  double unit_ = 0.0;
};

}  // namespace omninav::lattice
