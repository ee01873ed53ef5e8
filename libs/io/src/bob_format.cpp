#include "bob_format.hpp"

#include <fstream>
#include <opencv2/core/persistence.hpp>
#include <sstream>

#include "omninav/core/errors.hpp"

namespace omninav::io::bob {
namespace {

class MetadataParser {
 public:
  MetadataParser(const std::filesystem::path& file, cv::FileNode metadata)
      : file_(file), metadata_(std::move(metadata)) {}

  Metadata parse() const {
    Metadata parsed;
    if (const std::optional<std::string> type = text("type", metadata_)) {
      if (*type != "route" && *type != "grid") {
        fail("type", "is '" + *type + "', expected route or grid");
      }
      parsed.is_grid = *type == "grid";
      parsed.info.is_grid = *parsed.is_grid;
    }
    parsed.info.frame_rate_hz = number("frameRate", metadata_);
    if (parsed.info.frame_rate_hz && *parsed.info.frame_rate_hz <= 0.0) {
      // BoB writes 0 when the rate is unknown.
      parsed.info.frame_rate_hz.reset();
    }
    parsed.info.description = text("description", metadata_).value_or("");
    parsed.video_file = text("videoFile", metadata_).value_or("");
    if (const std::optional<double> flag = number("needsUnwrapping", metadata_)) {
      parsed.info.needs_unwrapping = *flag != 0.0;
    }

    const cv::FileNode camera = metadata_["camera"];
    if (camera.isMap()) {
      parsed.info.camera_name = text("name", camera).value_or("");
      parsed.info.image_size = resolution(camera["resolution"]);
      // BoB: "If needsUnwrapping is not explicitly set then assume that if the camera used was
      // panoramic then we want to unwrap it."
      if (!parsed.info.needs_unwrapping) {
        if (const std::optional<double> panoramic = number("isPanoramic", camera)) {
          parsed.info.needs_unwrapping = *panoramic != 0.0;
        }
      }
    } else if (!camera.empty()) {
      fail("camera", "is not a map");
    }
    return parsed;
  }

 private:
  std::optional<std::string> text(const char* key, const cv::FileNode& parent) const {
    const cv::FileNode node = parent[key];
    if (node.empty()) return std::nullopt;
    if (!node.isString()) fail(key, "is not text");
    return static_cast<std::string>(node);
  }

  std::optional<double> number(const char* key, const cv::FileNode& parent) const {
    const cv::FileNode node = parent[key];
    if (node.empty()) return std::nullopt;
    if (!node.isInt() && !node.isReal()) fail(key, "is not a number");
    return static_cast<double>(node);
  }

  cv::Size resolution(const cv::FileNode& node) const {
    if (node.empty()) return {};
    if (!node.isSeq() || node.size() != 2 || !node[0].isInt() || !node[1].isInt()) {
      fail("camera.resolution", "is not [width, height]");
    }
    return {static_cast<int>(node[0]), static_cast<int>(node[1])};
  }

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw InputError(file_.string() + ": metadata." + key + " " + problem);
  }

  std::filesystem::path file_;
  cv::FileNode metadata_;
};

}  // namespace

std::optional<Metadata> read_metadata(const std::filesystem::path& yaml_file) {
  std::error_code error;
  if (!std::filesystem::exists(yaml_file, error)) return std::nullopt;
  std::ifstream stream(yaml_file, std::ios::binary);
  if (!stream) throw InputError(yaml_file.string() + ": cannot open");
  std::ostringstream content;
  // As BoB does: prepend the directive, so that files written without it (by hand, or by BoB's
  // unwrap()) parse too; OpenCV skips the file's own directive line if it has one.
  content << "%YAML:1.0\n" << stream.rdbuf();
  try {
    const cv::FileStorage storage(content.str(), cv::FileStorage::READ | cv::FileStorage::MEMORY |
                                                     cv::FileStorage::FORMAT_YAML);
    const cv::FileNode metadata = storage["metadata"];
    if (!metadata.isMap()) throw InputError(yaml_file.string() + ": no 'metadata' map");
    return MetadataParser(yaml_file, metadata).parse();
  } catch (const cv::Exception& e) {
    throw InputError(yaml_file.string() + ": cannot parse YAML (" + e.err + ")");
  }
}

std::string metadata_yaml(const DatabaseInfo& info, bool greyscale) {
  cv::FileStorage storage(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  storage << "metadata"
          << "{";
  storage << "type" << (info.is_grid ? "grid" : "route");
  storage << "camera"
          << "{";
  storage << "name" << info.camera_name;
  storage << "resolution"
          << "[:" << info.image_size.width << info.image_size.height << "]";
  // BoB's reader takes isPanoramic (a raw omnidirectional camera) for needsUnwrapping when
  // that key is absent, so the two must agree.
  storage << "isPanoramic" << (info.needs_unwrapping.value_or(false) ? 1 : 0);
  storage << "}";
  if (info.needs_unwrapping) storage << "needsUnwrapping" << (*info.needs_unwrapping ? 1 : 0);
  storage << "isGreyscale" << (greyscale ? 1 : 0);
  if (info.frame_rate_hz) storage << "frameRate" << *info.frame_rate_hz;
  if (!info.description.empty()) storage << "description" << info.description;
  storage << "}";
  return storage.releaseAndGetString();
}

}  // namespace omninav::io::bob
