#pragma once
// Home vectors (compass/min_warping.hpp) where the commands and the evaluation need them: from a
// query panorama to a stored place (`localise --home-vector`), and their errors against the
// truth over pairs of grid places (`evaluate`'s home-vector columns).

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "omninav/compass/min_warping.hpp"
#include "omninav/evaluation/localisation_output.hpp"
#include "omninav/io/frame.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav::evaluation {

// The home vector from `query` to `place` (named `place_name` in messages): min-warping with the
// place's stored thumbnail as the snapshot and the query reduced to the thumbnail's size. The
// world direction when the place has a heading. Throws InputError naming the place when it has
// no thumbnail (explored with memory.yaml's thumbnail_width_px 0) and naming the query when it
// cannot be matched.
HomeVector home_vector_to_place(const compass::MinWarping& warping, const memory::Place& place,
                                const std::string& place_name, const cv::Mat& query,
                                const std::string& query_name);

// The errors of the home vectors of every pair of frames whose true positions are 1 to 3
// `spacing_m` apart (each pair once, the earlier frame the snapshot): the angle between the
// estimated and the true direction from the later frame's place to the earlier's, in the later
// frame. Frames without truth are skipped; featureless pairs are counted, not scored.
struct HomeVectorErrors {
  std::vector<double> errors_rad;  // |error| of each scored pair
  int featureless = 0;             // pairs with no estimate
  double median_deg() const;       // NaN when no pair was scored
  double p90_deg() const;          // the 90th percentile
};
HomeVectorErrors grid_home_vector_errors(const compass::MinWarping& warping,
                                         const std::vector<io::Frame>& frames, double spacing_m);

}  // namespace omninav::evaluation
