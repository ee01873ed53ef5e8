#pragma once
// Procedural textures for the built-in room. Each draws with its own cv::RNG, so a room is
// reproducible texel for texel from its seed. Sizes are in metres, resolution in px per metre;
// row 0 of every texture is its top edge.

#include <opencv2/core.hpp>

namespace omninav::sim::textures {

cv::Mat wall(double width_m, double height_m, double px_per_m, cv::RNG& rng);
// A wall of the given paint: with `decorated`, as wall() (wallpaper stripes or none, pictures,
// painted doors and windows); without, plain paint with stains and a skirting board.
cv::Mat painted_wall(double width_m, double height_m, double px_per_m, const cv::Scalar& paint,
                     bool decorated, cv::RNG& rng);
// A colour with each channel uniform in [low, high).
cv::Scalar random_colour(cv::RNG& rng, int low, int high);
// Adds smooth brightness variation (stains, uneven paint) at a scale of `cell_m`.
void add_smooth_noise(cv::Mat& image, double cell_m, double px_per_m, double amplitude,
                      cv::RNG& rng);
// A framed picture of random blocks, discs and bands inside `frame`.
void draw_picture(cv::Mat& image, cv::Rect frame, cv::RNG& rng);
cv::Mat floor(double width_m, double depth_m, double px_per_m, cv::RNG& rng);
// Wooden planks along the width, and wall-to-wall carpet with a border: a house's other floors.
cv::Mat planks(double width_m, double depth_m, double px_per_m, cv::RNG& rng);
cv::Mat carpet(double width_m, double depth_m, double px_per_m, cv::RNG& rng);
cv::Mat ceiling(double width_m, double depth_m, double px_per_m, cv::RNG& rng);
// One square metre of a furniture surface (tiled over the box's faces).
cv::Mat furniture(double px_per_m, cv::RNG& rng);

}  // namespace omninav::sim::textures
