#include "omninav/sim/renderer.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "omninav/core/angles.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/parse.hpp"
#include "texture_pyramid.hpp"

namespace omninav::sim {
namespace {

// Direction towards the light, for Lambert shading: above, from one side, so that walls facing
// different ways differ in brightness as they do in a real room.
const cv::Vec3f kToLight = cv::normalize(cv::Vec3f(0.35f, 0.55f, 0.75f));

// Heading is quantised to 2^-20 column so that headings a whole number of columns apart split
// into the same fraction exactly (see the header's note on exactness); 2^-20 column is 3e-7°.
constexpr double kHeadingQuantum = 1.0 / (1 << 20);

// log2 to within 0.09 for x ≥ 1 (exponent plus the mantissa's linear part): plenty to choose a
// texture level, and five times cheaper than std::log2, which showed in the profile.
inline float approximate_log2(float x) {
  const auto bits = std::bit_cast<std::uint32_t>(x);  // IEEE 754: x = 1.mantissa · 2^(e − 127)
  const auto exponent = static_cast<int>((bits >> 23) & 0xffu) - 127;
  const float mantissa = static_cast<float>(bits & 0x7fffffu) / static_cast<float>(1u << 23);
  return static_cast<float>(exponent) + mantissa;
}

struct Hit {
  float distance_m = std::numeric_limits<float>::infinity();
  cv::Vec3f colour;  // shaded, 0..255
};

// The occluder's box at `time_s`: it walks from one end to the other and back.
FloorBox occluder_footprint(const OccluderParams& occluder, double time_s) {
  const double dx = occluder.to_x_m - occluder.from_x_m;
  const double dy = occluder.to_y_m - occluder.from_y_m;
  const double length = std::hypot(dx, dy);
  double along = 0.0;
  if (length > 0.0) {
    along = std::fmod(std::abs(occluder.speed_m_s * time_s), 2.0 * length);
    if (along > length) along = 2.0 * length - along;
    along /= length;
  }
  const double x = occluder.from_x_m + dx * along;
  const double y = occluder.from_y_m + dy * along;
  const double half = occluder.width_m / 2.0;
  return {x - half, y - half, x + half, y + half};
}

// Slab test of a ray against an upright box; returns the entry distance and the entry face's
// normal, or nothing when the ray misses (or starts inside).
bool intersect_box(const cv::Vec3f& origin, const cv::Vec3f& direction, const cv::Vec3f& low,
                   const cv::Vec3f& high, float& distance, cv::Vec3f& normal) {
  float enter = 0.f, leave = std::numeric_limits<float>::infinity();
  int enter_axis = -1;
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(direction[axis]) < 1e-12f) {
      if (origin[axis] < low[axis] || origin[axis] > high[axis]) return false;
      continue;
    }
    float near = (low[axis] - origin[axis]) / direction[axis];
    float far = (high[axis] - origin[axis]) / direction[axis];
    if (near > far) std::swap(near, far);
    if (near > enter) {
      enter = near;
      enter_axis = axis;
    }
    leave = std::min(leave, far);
    if (enter > leave) return false;
  }
  if (enter_axis < 0) return false;
  distance = enter;
  normal = cv::Vec3f(0.f, 0.f, 0.f);
  normal[enter_axis] = direction[enter_axis] > 0.f ? -1.f : 1.f;
  return true;
}

}  // namespace

void load_render_params(const ConfigReader& section, RenderParams& params) {
  section.read("rays_per_pixel", params.rays_per_pixel, 1, 16);
  section.read("ambient", params.ambient, 0.0, 1.0);
  SensorEffects& effects = params.effects;
  section.read("noise_stddev", effects.noise_stddev, 0.0, 100.0);
  section.read("exposure_gain", effects.exposure_gain, 0.05, 20.0);
  int seed = static_cast<int>(effects.seed);
  section.read("seed", seed, 0, 1'000'000'000);
  effects.seed = static_cast<std::uint32_t>(seed);
  const ConfigReader occluder = section.section("occluder");
  OccluderParams& o = effects.occluder;
  occluder.read("enabled", o.enabled);
  occluder.read("from_x_m", o.from_x_m, -1e4, 1e4);
  occluder.read("from_y_m", o.from_y_m, -1e4, 1e4);
  occluder.read("to_x_m", o.to_x_m, -1e4, 1e4);
  occluder.read("to_y_m", o.to_y_m, -1e4, 1e4);
  occluder.read("speed_m_s", o.speed_m_s, 0.0, 100.0);
  occluder.read("width_m", o.width_m, 0.01, 10.0);
  occluder.read("height_m", o.height_m, 0.01, 10.0);
}

struct Renderer::Impl {
  RenderParams params;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;

  // Per triangle: material colour, texture (or -1), unit normal, corners' texture coordinates
  // and texels per metre (to choose the pyramid level from a ray's footprint).
  struct Surface {
    cv::Vec3f colour;
    int texture = -1;
    cv::Vec3f normal;
    std::array<cv::Vec2f, 3> uv;
    float texels_per_m = 1.f;
  };
  std::vector<Surface> surfaces;
  std::vector<TexturePyramid> textures;
  cv::Vec3f background;
  std::optional<cv::Vec3f> sky_zenith;  // see World::sky_zenith_bgr

  // The pixel's sample pattern (N-rooks, see the header): ray k is offset by column_offsets[k]
  // across, and its elevation in row r has cosine and sine cos/sin_elevation[k·H + r].
  std::vector<double> column_offsets;
  std::vector<float> cos_elevation, sin_elevation;
  float sample_angle_rad = 0.f;  // angle between neighbouring rays

  // The shaded colour and distance of a ray Embree has intersected.
  Hit shade(const RTCRayHit& ray) const;

  // Sets `rays` (every sample of every row of one column, rows fastest) to start at `origin`
  // and look along the directions of world column `world_column`, turned by `fraction` of a
  // column and tilted by `tilt`.
  void aim_column(int world_column, double fraction, const cv::Matx33f& tilt,
                  const cv::Vec3f& origin, std::vector<RTCRayHit>& rays) const;
};

Renderer::Renderer(const World& world, const RenderParams& params)
    : impl_(std::make_unique<Impl>()) {
  Impl& impl = *impl_;
  impl.params = params;
  impl.background = world.background_bgr;
  impl.sky_zenith = world.sky_zenith_bgr;
  if (world.triangles.empty())
    throw UsageError("renderer: the world '" + world.name + "' is empty");

  for (const cv::Mat& texture : world.textures) impl.textures.emplace_back(texture);
  impl.surfaces.reserve(world.triangles.size());
  for (const Triangle& triangle : world.triangles) {
    const Material& material = world.materials.at(triangle.material);
    const cv::Vec3f a = world.vertices.at(triangle.vertex[0]);
    const cv::Vec3f b = world.vertices.at(triangle.vertex[1]);
    const cv::Vec3f c = world.vertices.at(triangle.vertex[2]);
    const cv::Vec3f cross = (b - a).cross(c - a);
    const float world_area = 0.5f * static_cast<float>(cv::norm(cross));
    Impl::Surface surface;
    surface.colour = material.colour_bgr / 255.f;
    surface.texture = material.texture;
    surface.normal = world_area > 0.f ? cross / (2.f * world_area) : cv::Vec3f(0.f, 0.f, 1.f);
    surface.uv = triangle.uv;
    if (material.texture >= 0 && world_area > 0.f) {
      const cv::Size size = world.textures[material.texture].size();
      const cv::Vec2f du = triangle.uv[1] - triangle.uv[0];
      const cv::Vec2f dv = triangle.uv[2] - triangle.uv[0];
      const float uv_area =
          0.5f * std::abs(du[0] * dv[1] - du[1] * dv[0]) * size.width * size.height;
      surface.texels_per_m = std::sqrt(uv_area / world_area);
    }
    impl.surfaces.push_back(surface);
  }

  // One BVH over every triangle; the geometry's primitive ID is the World triangle index.
  impl.device = rtcNewDevice("threads=1");
  if (!impl.device) throw Error("renderer: cannot create an Embree device");
  impl.scene = rtcNewScene(impl.device);
  rtcSetSceneBuildQuality(impl.scene, RTC_BUILD_QUALITY_HIGH);
  // Watertight: a ray through the edge two triangles share hits one of them. Without it, the
  // rays of a camera standing on the line of a long edge (the diagonal of a field's ground,
  // through its centre) slip through it and draw a line of background.
  rtcSetSceneFlags(impl.scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geometry = rtcNewGeometry(impl.device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                               RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                               world.vertices.size()));
  for (std::size_t i = 0; i < world.vertices.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) vertices[3 * i + axis] = world.vertices[i][axis];
  }
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), world.triangles.size()));
  for (std::size_t i = 0; i < world.triangles.size(); ++i) {
    for (int corner = 0; corner < 3; ++corner) {
      indices[3 * i + corner] = static_cast<unsigned>(world.triangles[i].vertex[corner]);
    }
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(impl.scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(impl.scene);

  const PanoramaGeometry& panorama = params.geometry;
  // N-rooks: ray k sits in sub-column k and sub-row perm(k), a permutation that spreads the
  // rays over the pixel, so N rays give N distinct offsets along both axes (a regular grid
  // would need N² rays for that).
  const int samples = std::max(1, params.rays_per_pixel);
  int stride = std::max(1, static_cast<int>(std::lround(samples * 0.618)));
  while (std::gcd(stride, samples) != 1) ++stride;
  for (int ray = 0; ray < samples; ++ray) {
    impl.column_offsets.push_back((ray + 0.5) / samples - 0.5);
    const double row_offset = ((ray * stride) % samples + 0.5) / samples - 0.5;
    for (int row = 0; row < panorama.height_px; ++row) {
      const double elevation = panorama.elevation_of_row(row + row_offset);
      impl.cos_elevation.push_back(static_cast<float>(std::cos(elevation)));
      impl.sin_elevation.push_back(static_cast<float>(std::sin(elevation)));
    }
  }
  // Rays are 1/√N pixel apart on average: the footprint that picks the texture level.
  impl.sample_angle_rad = static_cast<float>(kTwoPi / panorama.width_px / std::sqrt(samples));
}

Renderer::~Renderer() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

const RenderParams& Renderer::params() const {
  return impl_->params;
}

Hit Renderer::Impl::shade(const RTCRayHit& ray) const {
  const cv::Vec3f direction(ray.ray.dir_x, ray.ray.dir_y, ray.ray.dir_z);
  Hit hit;
  if (ray.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
    hit.colour = background;
    if (sky_zenith && direction[2] > 0.f) {
      // Blends with the square root of the elevation's sine: the sky is pale only near the
      // horizon, as a clear sky is.
      const float blend = std::sqrt(std::min(direction[2], 1.f));
      hit.colour = (1.f - blend) * background + blend * *sky_zenith;
    }
    return hit;
  }
  hit.distance_m = ray.ray.tfar;
  const Surface& surface = surfaces[ray.hit.primID];
  float facing = surface.normal.dot(direction);
  const cv::Vec3f normal = facing > 0.f ? -surface.normal : surface.normal;  // two-sided
  facing = std::abs(facing);
  cv::Vec3f albedo = surface.colour;
  if (surface.texture >= 0) {
    const float u = ray.hit.u, v = ray.hit.v;
    const cv::Vec2f uv = (1.f - u - v) * surface.uv[0] + u * surface.uv[1] + v * surface.uv[2];
    // Footprint of one ray on the surface, in texels: grows with distance and obliquity.
    const float footprint_m = hit.distance_m * sample_angle_rad / std::max(facing, 0.2f);
    const float level = approximate_log2(std::max(footprint_m * surface.texels_per_m, 1.f));
    albedo = albedo.mul(textures[surface.texture].sample(uv, level));
  }
  const float light =
      static_cast<float>(params.ambient) +
      static_cast<float>(1.0 - params.ambient) * std::max(0.f, normal.dot(kToLight));
  hit.colour = albedo * (255.f * light);
  return hit;
}

void Renderer::Impl::aim_column(int world_column, double fraction, const cv::Matx33f& tilt,
                                const cv::Vec3f& origin, std::vector<RTCRayHit>& rays) const {
  const int width = params.geometry.width_px;
  const int height = params.geometry.height_px;
  for (std::size_t sample = 0; sample < column_offsets.size(); ++sample) {
    const double azimuth =
        kPi / 2.0 - kTwoPi * (world_column + column_offsets[sample] - fraction) / width;
    const float cos_azimuth = static_cast<float>(std::cos(azimuth));
    const float sin_azimuth = static_cast<float>(std::sin(azimuth));
    for (int row = 0; row < height; ++row) {
      const std::size_t sub_row = sample * static_cast<std::size_t>(height) + row;
      const cv::Vec3f level(cos_elevation[sub_row] * cos_azimuth,
                            cos_elevation[sub_row] * sin_azimuth, sin_elevation[sub_row]);
      const cv::Vec3f direction = tilt * level;
      RTCRayHit& ray = rays[sub_row];
      ray.ray.org_x = origin[0];
      ray.ray.org_y = origin[1];
      ray.ray.org_z = origin[2];
      ray.ray.dir_x = direction[0];
      ray.ray.dir_y = direction[1];
      ray.ray.dir_z = direction[2];
      ray.ray.tnear = 1e-4f;
      ray.ray.tfar = std::numeric_limits<float>::infinity();
      ray.ray.mask = std::numeric_limits<unsigned>::max();
      ray.ray.flags = 0;
      ray.ray.time = 0.f;
      ray.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      ray.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
  }
}

namespace {

// A heading in columns, split into the whole columns the panorama rolls by and the fraction
// of a column its rays turn by (see kHeadingQuantum).
struct HeadingInColumns {
  int shift = 0;
  double fraction = 0.0;
};

HeadingInColumns heading_in_columns(double heading_rad, int width) {
  const double heading_columns =
      std::round(heading_rad * width / kTwoPi / kHeadingQuantum) * kHeadingQuantum;
  const double whole_columns = std::floor(heading_columns);
  return {static_cast<int>(std::fmod(whole_columns, width)), heading_columns - whole_columns};
}

// Tilt in the level frame: M = Rz(θ)·Ry(pitch)·Rx(roll)·Rz(−θ) takes a direction of the
// un-tilted camera (azimuth measured in the world) to the tilted one. Exactly the identity
// when pitch and roll are zero, which keeps whole-column turns bit-exact.
cv::Matx33f tilt_of(const CameraPose& pose) {
  if (pose.pitch_rad == 0.0 && pose.roll_rad == 0.0) return cv::Matx33f::eye();
  const double ch = std::cos(pose.heading_rad), sh = std::sin(pose.heading_rad);
  const double cp = std::cos(pose.pitch_rad), sp = std::sin(pose.pitch_rad);
  const double cr = std::cos(pose.roll_rad), sr = std::sin(pose.roll_rad);
  const cv::Matx33d yaw(ch, -sh, 0, sh, ch, 0, 0, 0, 1);
  const cv::Matx33d pitch(cp, 0, sp, 0, 1, 0, -sp, 0, cp);
  const cv::Matx33d roll(1, 0, 0, 0, cr, -sr, 0, sr, cr);
  return cv::Matx33f(yaw * pitch * roll * yaw.t());
}

// The moving occluder at one time, as the box a ray may hit (sensor effects).
class Occluder {
 public:
  Occluder(const OccluderParams& params, double time_s, double ambient)
      : params_(params), ambient_(ambient) {
    if (!params.enabled) return;
    const FloorBox box = occluder_footprint(params, time_s);
    low_ = cv::Vec3f(static_cast<float>(box.min_x_m), static_cast<float>(box.min_y_m), 0.f);
    high_ = cv::Vec3f(static_cast<float>(box.max_x_m), static_cast<float>(box.max_y_m),
                      static_cast<float>(params.height_m));
  }

  // Colours `hit` with the occluder when the ray from `origin` along `direction` meets it
  // before what it hit.
  void cover(const cv::Vec3f& origin, const cv::Vec3f& direction, Hit& hit) const {
    if (!params_.enabled) return;
    float distance = 0.f;
    cv::Vec3f normal;
    if (intersect_box(origin, direction, low_, high_, distance, normal) &&
        distance < hit.distance_m) {
      const float light = static_cast<float>(ambient_) +
                          static_cast<float>(1.0 - ambient_) * std::max(0.f, normal.dot(kToLight));
      hit.colour = params_.colour_bgr * light;
    }
  }

 private:
  const OccluderParams& params_;
  double ambient_ = 0.0;
  cv::Vec3f low_, high_;
};

}  // namespace

cv::Mat Renderer::render(const CameraPose& pose, double time_s, int frame_index) const {
  // Embree asserts (aborts) on rays from NaN or overflowing origins: refused here first.
  check_pose(pose, "the camera pose");
  if (!std::isfinite(time_s))
    throw InputError("render: time " + general(time_s) + " s is not finite");
  const Impl& impl = *impl_;
  const int width = impl.params.geometry.width_px;
  const int height = impl.params.geometry.height_px;
  const int samples = static_cast<int>(impl.column_offsets.size());
  const HeadingInColumns heading = heading_in_columns(pose.heading_rad, width);
  const cv::Matx33f tilt = tilt_of(pose);
  const cv::Vec3f origin(static_cast<float>(pose.x_m), static_cast<float>(pose.y_m),
                         static_cast<float>(pose.z_m));
  const Occluder occluder(impl.params.effects.occluder, time_s, impl.params.ambient);

  // One column's rays go to Embree together, flagged coherent: they fan out from one point
  // within a narrow wedge, which its stream traversal exploits (about twice as fast as one
  // ray at a time here).
  std::vector<RTCRayHit> rays(impl.cos_elevation.size());
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;

  const SensorEffects& effects = impl.params.effects;
  const float gain = static_cast<float>(effects.exposure_gain / samples);
  cv::RNG noise((static_cast<std::uint64_t>(effects.seed) << 32) ^
                static_cast<std::uint32_t>(frame_index) ^ 0x9e3779b97f4a7c15ULL);
  std::vector<cv::Vec3f> column_sum(height);
  cv::Mat panorama_8u(height, width, CV_8UC3);
  for (int column = 0; column < width; ++column) {
    // Column `column` at heading s looks where column (column − s) looks at heading 0.
    const int world_column = ((column - heading.shift) % width + width) % width;
    impl.aim_column(world_column, heading.fraction, tilt, origin, rays);
    rtcIntersect1M(impl.scene, &context, rays.data(), static_cast<unsigned>(rays.size()),
                   sizeof(RTCRayHit));
    for (std::size_t index = 0; index < rays.size(); ++index) {
      Hit hit = impl.shade(rays[index]);
      occluder.cover(origin,
                     cv::Vec3f(rays[index].ray.dir_x, rays[index].ray.dir_y, rays[index].ray.dir_z),
                     hit);
      column_sum[index % height] += hit.colour;
    }
    for (int row = 0; row < height; ++row) {
      cv::Vec3f value = column_sum[row] * gain;
      if (effects.noise_stddev > 0.0) {
        for (int channel = 0; channel < 3; ++channel) {
          value[channel] += static_cast<float>(noise.gaussian(effects.noise_stddev));
        }
      }
      panorama_8u.at<cv::Vec3b>(row, column) =
          cv::Vec3b(cv::saturate_cast<uchar>(value[0]), cv::saturate_cast<uchar>(value[1]),
                    cv::saturate_cast<uchar>(value[2]));
      column_sum[row] = cv::Vec3f(0.f, 0.f, 0.f);
    }
  }
  return panorama_8u;
}

}  // namespace omninav::sim
