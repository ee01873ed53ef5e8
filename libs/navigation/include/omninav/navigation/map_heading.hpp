#pragma once
// The heading a view measures against a map: its best place, when recognised (recognition_limit,
// memory_places.hpp), and that place's heading plus the turn between the place's signature and
// the view from the phases (memory::PlaceMatch::heading_rad; Menegatti et al. 2004, Eq. 1). What
// a visual compass re-aligns on: "only requiring infrequent re-alignment, for example when
// re-localising in a topological map" (Labrosse 2006, abstract).

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "omninav/memory/localisation.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/navigation/navigator.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::navigation {

struct MapHeading {
  memory::PlaceIndex place = 0;  // the recognised best place
  double heading_rad = 0.0;      // the view's heading in the map's frame (the places' headings')
  // The spread of the other recognised best places' readings of the same heading (each place's
  // heading plus its phase turn to the view): the RMS of their differences from the best
  // place's, radians; infinite when the best place is the only one recognised with a heading.
  // Measured on the view, not fitted: on the full suite's routes re-aligned on every recognised
  // frame, |error| of the reading exceeded 10° on 1 % of frames with a spread of 1-4°, 3 % at
  // 4-8°, 30 % above 16°, and 26 % of frames with a single recognised place (docs/compass.md).
  double spread_rad = 0.0;
  double dissimilarity_per_value = 0.0;  // the best place's (memory::PlaceMatch)
};

// When a compass re-aligns on a map's reading (`omninav compass --map`; docs/compass.md
// "Re-alignment on a map").
struct RealignmentParams {
  // The innovation gate: a reading more than this many combined standard deviations
  // (hypot(compass sigma, reading spread)) from the compass's heading is a look-alike's and is
  // left out. Chosen across the zoo (docs/compass.md): of 2, 3, 5 and no gate on the circle,
  // wander and bumpy routes of 11 full-suite rows, 5 has the lowest mean max |e| over the
  // families (24.3° against 29.2° without the map); no gate loses the Ofstad arena (53.5 ->
  // 122°), whose symmetric views put several places' readings 150-175° off.
  double gate_sigmas = 5.0;
};

// Whether a compass whose heading is heading_rad ± sigma_rad (its heading_sigma) re-aligns on
// `reading`: the reading's spread is finite and below the compass's sigma (the map is surer than
// the compass), and within the gate of its heading; or the compass is not in the map's frame yet
// (`in_map_frame` false: started without a true heading), when a finite spread is enough.
bool realigns(const MapHeading& reading, double heading_rad, double sigma_rad, bool in_map_frame,
              const RealignmentParams& params = {});

// The headings of views measured against `memory` (which must outlive it): each view localised
// by memory::Localiser, its best place recognised when its dissimilarity per value is within
// recognition_limit (memory_places.hpp).
class MapHeadings {
 public:
  MapHeadings(const memory::VisualMemory& memory, const memory::LocalisationParams& localisation);

  // None when the view's best place is not recognised or has no heading. Throws InputError for
  // a panorama of another height than the map's.
  std::optional<MapHeading> measure(const cv::Mat& panorama);

  const memory::VisualMemory& memory() const { return localiser_.memory(); }

 private:
  memory::Localiser localiser_;
  signature::SignatureExtractor extractor_;
  double limit_;
};

}  // namespace omninav::navigation
