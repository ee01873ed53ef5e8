// Wavefront OBJ worlds, parsed with tinyobjloader (Debian's libtinyobjloader-dev) rather than
// by hand: it handles polygons, negative indices and MTL files as the format intends.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>

#include "omninav/core/errors.hpp"
#include "omninav/core/image_size.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/parse.hpp"
#include "omninav/sim/world.hpp"

namespace omninav::sim {
namespace {

cv::Vec3f to_world(const float* xyz, const ObjWorldParams& params) {
  const float scale = static_cast<float>(params.scale_to_m);
  if (params.y_up) return {xyz[0] * scale, -xyz[2] * scale, xyz[1] * scale};
  return {xyz[0] * scale, xyz[1] * scale, xyz[2] * scale};
}

// The largest texture coordinate accepted: a texture repeats, and beyond a float's 2^24 its
// fraction (where in the texture a point lies) is lost; the renderer wraps with integers.
constexpr double kMaxTextureCoordinate = 1e6;

// tinyobjloader reads a coordinate it cannot parse ("nan", "inf") as 0, silently: the vertex
// lines ("v x y z [w]") are checked first, each coordinate a finite number, and the texture
// coordinate lines ("vt u v [w]"), each within ±kMaxTextureCoordinate.
void check_vertex_lines(const std::filesystem::path& obj_file) {
  std::ifstream stream(obj_file, std::ios::binary);
  std::string line;
  for (int number = 1; std::getline(stream, line); ++number) {
    std::istringstream fields(line);
    std::string tag;
    if (!(fields >> tag) || (tag != "v" && tag != "vt")) continue;
    const bool texture = tag == "vt";
    std::string field;
    for (int axis = 0; axis < (texture ? 2 : 3) && fields >> field; ++axis) {
      double value = 0.0;
      const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
      if (error != std::errc() || end != field.data() + field.size() || !std::isfinite(value)) {
        throw InputError(obj_file.string() + ":" + std::to_string(number) + ": " +
                         (texture ? "texture" : "vertex") + " coordinate '" +
                         printable_name(field) + "' is not a finite number");
      }
      if (texture && std::abs(value) > kMaxTextureCoordinate) {
        throw InputError(obj_file.string() + ":" + std::to_string(number) +
                         ": texture coordinate '" + printable_name(field) +
                         "' is beyond ±1e6 (a texture repeats; no renderer can place a point "
                         "that far along it)");
      }
    }
  }
}

}  // namespace

World load_obj_world(const std::filesystem::path& obj_file, const ObjWorldParams& params) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(obj_file, error)) {
    // A FIFO or a device is named for what it is, and never opened (a FIFO would block).
    throw InputError(obj_file.string() + ": " + unreadable_file_reason(obj_file, "OBJ file"));
  }
  check_vertex_lines(obj_file);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.mtl_search_path = obj_file.parent_path().string();
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(obj_file.string(), config)) {
    throw InputError(obj_file.string() + ": cannot parse OBJ: " + reader.Error());
  }
  if (!reader.Warning().empty()) log_debug(obj_file.string() + ": " + reader.Warning());

  World world;
  world.name = obj_file.stem().string();
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3) {
    world.vertices.push_back(to_world(&attrib.vertices[i], params));
    // The bound of every position (core/pose.hpp): NaN, inf or 1e30 m is damage, not a world.
    const std::string where =
        obj_file.string() + ": vertex " + std::to_string(world.vertices.size());
    for (int axis = 0; axis < 3; ++axis) {
      check_coordinate_m(world.vertices.back()[axis], where + " " + "xyz"[axis]);
    }
  }
  for (const tinyobj::material_t& source : reader.GetMaterials()) {
    Material material;
    material.name = source.name;
    material.colour_bgr =
        cv::Vec3f(source.diffuse[2], source.diffuse[1], source.diffuse[0]) * 255.f;
    if (!source.diffuse_texname.empty()) {
      const std::filesystem::path texture_file = obj_file.parent_path() / source.diffuse_texname;
      // A texture is an image file like any other: its decoded size is bounded as an input
      // image's, from its header before decoding and from the image after.
      check_declared_image_pixels(texture_file);
      cv::Mat texture = cv::imread(texture_file.string(), cv::IMREAD_COLOR);
      if (texture.empty()) {
        throw InputError(texture_file.string() + ": cannot read the texture of material '" +
                         source.name + "' in " + obj_file.string());
      }
      check_image_pixels(texture.size(), texture_file.string());
      world.textures.push_back(texture);
      material.texture = static_cast<int>(world.textures.size()) - 1;
    }
    world.materials.push_back(material);
  }
  const int default_material = static_cast<int>(world.materials.size());
  world.materials.push_back({"default", {200.f, 200.f, 200.f}, -1});

  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    for (std::size_t face = 0; face < shape.mesh.num_face_vertices.size(); ++face) {
      Triangle triangle;
      if (shape.mesh.num_face_vertices[face] != 3 || indices.size() < 3 * face + 3) {
        throw InputError(obj_file.string() + ": a face of shape '" + shape.name +
                         "' is not a triangle after triangulation");
      }
      for (int corner = 0; corner < 3; ++corner) {
        const tinyobj::index_t& index = indices[3 * face + corner];
        const bool vertex_known =
            index.vertex_index >= 0 &&
            static_cast<std::size_t>(index.vertex_index) < world.vertices.size();
        const bool texcoord_known =
            index.texcoord_index < 0 ||
            2 * static_cast<std::size_t>(index.texcoord_index) + 1 < attrib.texcoords.size();
        if (!vertex_known || !texcoord_known) {
          throw InputError(obj_file.string() + ": a face of shape '" + shape.name +
                           "' names a vertex or texture coordinate the file does not have");
        }
        triangle.vertex[corner] = index.vertex_index;
        if (index.texcoord_index >= 0) {
          triangle.uv[corner] = {attrib.texcoords[2 * index.texcoord_index],
                                 attrib.texcoords[2 * index.texcoord_index + 1]};
        }
      }
      const int material_id =
          face < shape.mesh.material_ids.size() ? shape.mesh.material_ids[face] : -1;
      triangle.material =
          material_id >= 0 && material_id < default_material ? material_id : default_material;
      world.triangles.push_back(triangle);
    }
  }
  if (world.triangles.empty()) throw InputError(obj_file.string() + ": the OBJ has no faces");

  // The free area of an OBJ world is its bounding box: we know nothing of its furniture.
  float min_x = std::numeric_limits<float>::max(), min_y = min_x;
  float max_x = std::numeric_limits<float>::lowest(), max_y = max_x;
  for (const cv::Vec3f& vertex : world.vertices) {
    min_x = std::min(min_x, vertex[0]);
    max_x = std::max(max_x, vertex[0]);
    min_y = std::min(min_y, vertex[1]);
    max_y = std::max(max_y, vertex[1]);
  }
  world.floor = {min_x, min_y, max_x, max_y};
  return world;
}

}  // namespace omninav::sim
