#pragma once
// Procedural textures for the built-in room. Each draws with its own cv::RNG, so a room is
// reproducible texel for texel from its seed. Sizes are in metres, resolution in px per metre;
// row 0 of every texture is its top edge.

#include <opencv2/core.hpp>

namespace omninav::sim::textures {

cv::Mat wall(double width_m, double height_m, double px_per_m, cv::RNG& rng);
cv::Mat floor(double width_m, double depth_m, double px_per_m, cv::RNG& rng);
cv::Mat ceiling(double width_m, double depth_m, double px_per_m, cv::RNG& rng);
// One square metre of a furniture surface (tiled over the box's faces).
cv::Mat furniture(double px_per_m, cv::RNG& rng);

}  // namespace omninav::sim::textures
