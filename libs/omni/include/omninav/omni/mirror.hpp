#pragma once
// Finding the mirror in a raw omnidirectional image: a bright(ish) disc, the mirror reflecting
// the lit room, on a darker surround (the camera housing, or the part of the sensor outside
// the mirror's image).

#include <opencv2/core.hpp>
#include <optional>

namespace omninav::omni {

struct MirrorCircle {
  cv::Point2d centre_px;   // OpenCV pixel coordinates: pixel (column j, row i) centred at (j, i)
  double radius_px = 0.0;  // the rim
};

// The mirror's rim in `raw` (8-bit or any depth, 1, 3 or 4 channels), or nothing when no
// disc-like region of clearly brighter pixels stands out. Method: blur, Otsu threshold,
// morphological clean-up, the largest outer contour, then a least-squares circle through its
// points that do not lie on the image border (so a disc cropped by the image edges is still
// measured by its visible rim). The disc may have holes (a dark centre: the camera itself).
std::optional<MirrorCircle> find_mirror_circle(const cv::Mat& raw);

}  // namespace omninav::omni
