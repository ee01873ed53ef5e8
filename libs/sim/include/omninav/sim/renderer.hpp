#pragma once
// The panoramic renderer: draws the panorama a camera at any pose (x, y, z, heading, pitch,
// roll) sees in a World, with the column convention of docs/design.md and the rows of a
// PanoramaGeometry. Rays are cast with Intel Embree (Debian's libembree-dev): a well-kept BVH
// and intersection kernel, far faster than anything we would write.
//
// Anti-aliasing: each pixel averages N rays on an N-rooks pattern (N distinct offsets along
// each axis, one ray per sub-column and per sub-row), and textures are sampled from a Gaussian
// pyramid at the level matching a ray's footprint (trilinear), so that a sub-column rotation
// changes the image smoothly.
//
// Exactness: with zero pitch and roll, a turn by a whole number of columns casts bit-identical
// rays into rolled columns, so render(θ + k·2π/W) == roll_columns(render(θ), k) exactly.

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>

#include "omninav/core/panorama.hpp"
#include "omninav/core/pose.hpp"
#include "omninav/sim/world.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::sim {

// A moving occluder (a person walking by): an upright box that goes back and forth between
// two floor points at constant speed.
struct OccluderParams {
  bool enabled = false;
  double from_x_m = 1.0, from_y_m = 1.0;  // one end of its walk
  double to_x_m = 4.0, to_y_m = 1.0;      // the other end
  double speed_m_s = 0.5;
  double width_m = 0.4;  // square footprint side
  double height_m = 1.7;
  cv::Vec3f colour_bgr{60.f, 40.f, 150.f};
};

struct SensorEffects {
  double noise_stddev = 0.0;   // Gaussian pixel noise, grey levels (0..255 scale)
  double exposure_gain = 1.0;  // multiplies every pixel (1 = unchanged)
  OccluderParams occluder;
  std::uint32_t seed = 1;  // noise is seeded by (seed, frame index): reproducible
};

struct RenderParams {
  PanoramaGeometry geometry;  // size and vertical field of view, from camera.yaml
  int rays_per_pixel = 3;     // anti-aliasing samples, on an N-rooks pattern (1 = none)
  double ambient = 0.55;      // share of light reaching every surface
  SensorEffects effects;
};

// Reads the `render:` section of worlds.yaml (rays_per_pixel, ambient, noise_stddev,
// exposure_gain, seed, and an `occluder:` subsection).
void load_render_params(const ConfigReader& section, RenderParams& params);

class Renderer {
 public:
  Renderer(const World& world, const RenderParams& params);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // The 8-bit BGR panorama at `pose`. `time_s` places the moving occluder; `frame_index`
  // seeds the noise. InputError for a pose check_pose refuses (NaN, inf, beyond ±1e7 m) or a
  // time that is not finite.
  cv::Mat render(const CameraPose& pose, double time_s = 0.0, int frame_index = 0) const;

  const RenderParams& params() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace omninav::sim
