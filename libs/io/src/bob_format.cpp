#include "bob_format.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <opencv2/core/persistence.hpp>
#include <sstream>

#include "omninav/core/errors.hpp"

namespace omninav::io::bob {
namespace {

// Reads the `metadata` map of database_metadata.yaml. BoB writes and reads the file with
// OpenCV's cv::FileStorage; omninav reads it with yaml-cpp instead, because OpenCV's YAML parser
// is not safe on damaged input: it overflowed its stack on deep nesting, threw
// std::length_error on a key with no name, and looped forever on the 12 bytes " - a\nt\"\nb"
// (the last two found by tests/fuzz/bob_metadata_fuzz.cpp). The keys BoB writes are plain
// YAML, which both read alike.
class MetadataParser {
 public:
  MetadataParser(const std::filesystem::path& file, YAML::Node metadata)
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

    const YAML::Node camera = metadata_["camera"];
    if (camera.IsDefined() && camera.IsMap()) {
      parsed.info.camera_name = text("name", camera).value_or("");
      parsed.info.image_size = resolution(camera["resolution"]);
      // BoB: "If needsUnwrapping is not explicitly set then assume that if the camera used was
      // panoramic then we want to unwrap it."
      if (!parsed.info.needs_unwrapping) {
        if (const std::optional<double> panoramic = number("isPanoramic", camera)) {
          parsed.info.needs_unwrapping = *panoramic != 0.0;
        }
      }
    } else if (camera.IsDefined() && !camera.IsNull()) {
      fail("camera", "is not a map");
    }

    const YAML::Node grid = metadata_["grid"];
    if (grid.IsDefined() && grid.IsMap()) {
      GridGeometry geometry;
      geometry.begin_mm = triple("grid.beginAtMM", grid["beginAtMM"], -1e12);
      geometry.separation_mm = triple("grid.separationMM", grid["separationMM"], 0.0);
      const std::array<double, 3> size = triple("grid.size", grid["size"], 0.0);
      for (std::size_t i = 0; i < 3; ++i) {
        if (size[i] != std::floor(size[i]) || size[i] > 1e9)
          fail("grid.size", "is not [nx, ny, nz]");
        geometry.size[i] = static_cast<int>(size[i]);
      }
      parsed.info.grid = geometry;
    } else if (grid.IsDefined() && !grid.IsNull()) {
      fail("grid", "is not a map");
    }
    return parsed;
  }

 private:
  static bool absent(const YAML::Node& node) { return !node.IsDefined() || node.IsNull(); }

  std::optional<std::string> text(const char* key, const YAML::Node& parent) const {
    const YAML::Node node = parent[key];
    if (absent(node)) return std::nullopt;
    if (!node.IsScalar()) fail(key, "is not text");
    return node.Scalar();
  }

  std::optional<double> number(const char* key, const YAML::Node& parent) const {
    const YAML::Node node = parent[key];
    if (absent(node)) return std::nullopt;
    double value = 0.0;
    if (!node.IsScalar() || !YAML::convert<double>::decode(node, value)) {
      fail(key, "is not a number");
    }
    if (!std::isfinite(value)) fail(key, "is not a finite number");  // YAML has .nan and .inf
    return value;
  }

  // [x, y, z], each finite and at least `least`; [0, 0, 0] when absent.
  std::array<double, 3> triple(const std::string& key, const YAML::Node& node, double least) const {
    std::array<double, 3> values{};
    if (absent(node)) return values;
    if (!node.IsSequence() || node.size() != 3) fail(key, "is not [x, y, z]");
    for (std::size_t i = 0; i < 3; ++i) {
      if (!node[i].IsScalar() || !YAML::convert<double>::decode(node[i], values[i]) ||
          !std::isfinite(values[i]) || values[i] < least) {
        fail(key, "is not [x, y, z] of finite numbers" + std::string(least == 0.0 ? " >= 0" : ""));
      }
    }
    return values;
  }

  cv::Size resolution(const YAML::Node& node) const {
    if (absent(node)) return {};
    int width = 0, height = 0;
    if (!node.IsSequence() || node.size() != 2 || !node[0].IsScalar() || !node[1].IsScalar() ||
        !YAML::convert<int>::decode(node[0], width) ||
        !YAML::convert<int>::decode(node[1], height) || width < 1 || height < 1) {
      fail("camera.resolution", "is not [width, height] in pixels");
    }
    return {width, height};
  }

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw InputError(file_.string() + ": metadata." + key + " " + problem);
  }

  std::filesystem::path file_;
  YAML::Node metadata_;
};

// BoB's metadata is a few hundred bytes, nested three levels deep. YAML parsers recurse once
// per level of nesting (OpenCV's overflowed its stack on a file of 50,000 brackets; yaml-cpp
// stops at 2,000 levels): the size and depth are bounded here, before any parser sees the
// text, with a message that says what is wrong.
constexpr std::size_t kMaxMetadataBytes = 64 * 1024;
constexpr int kMaxMetadataDepth = 32;

// An upper bound of the nesting a parser would follow: flow brackets ([ and {) still open, plus,
// at the start of each line, its indentation and its "- " sequence markers (each of which can
// open a block collection). Brackets inside a quoted scalar or a comment are text; a quote or
// comment ends at the end of its line here, so that the bound errs only on the safe side.
void check_nesting(const std::string& text, const std::filesystem::path& file) {
  if (text.size() > kMaxMetadataBytes) {
    throw InputError(file.string() + ": " + std::to_string(text.size()) +
                     " bytes, too large for BoB metadata (at most " +
                     std::to_string(kMaxMetadataBytes) + ")");
  }
  int flow_depth = 0;
  int line_depth = 0;  // indentation and sequence markers of the current line
  bool line_start = true;
  char quote = 0;     // the quote character of a quoted scalar being read
  char previous = 0;  // the last character outside quotes on this line that was not blank
  bool blank_before = true;
  bool comment = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const bool blank = c == ' ' || c == '\t' || c == '\r';
    if (c == '\n') {
      line_start = blank_before = true;
      line_depth = 0;
      quote = previous = 0;
      comment = false;
      continue;
    }
    if (line_start) {
      if (blank ||
          (c == '-' && i + 1 < text.size() && (text[i + 1] == ' ' || text[i + 1] == '\t'))) {
        ++line_depth;
      } else {
        line_start = false;
      }
    }
    if (comment) continue;
    if (quote != 0) {
      if (c == quote) quote = 0;
    } else if ((c == '"' || c == '\'') && (previous == 0 || std::strchr(":-[{,", previous))) {
      quote = c;
    } else if (c == '#' && blank_before) {
      comment = true;
    } else if (c == '[' || c == '{') {
      ++flow_depth;
    } else if ((c == ']' || c == '}') && flow_depth > 0) {
      --flow_depth;
    }
    if (!blank && quote == 0) previous = c;
    blank_before = blank;
    if (flow_depth + line_depth > kMaxMetadataDepth) {
      throw InputError(file.string() + ": nested more than " + std::to_string(kMaxMetadataDepth) +
                       " levels deep (indentation included), not BoB metadata");
    }
  }
}

}  // namespace

std::optional<Metadata> read_metadata(const std::filesystem::path& yaml_file) {
  std::error_code error;
  if (!std::filesystem::exists(yaml_file, error)) return std::nullopt;
  std::ifstream stream(yaml_file, std::ios::binary);
  if (!stream) throw InputError(yaml_file.string() + ": cannot open");
  std::ostringstream file_text;
  file_text << stream.rdbuf();
  if (stream.bad()) throw InputError(yaml_file.string() + ": read error");
  std::string content = file_text.str();
  check_nesting(content, yaml_file);
  // OpenCV's own directive, "%YAML:1.0" (not YAML's "%YAML 1.0"), which BoB's files may or may
  // not start with, is not YAML: it is dropped, as OpenCV itself skips it.
  if (content.starts_with("%YAML:")) content.erase(0, content.find('\n'));
  try {
    const YAML::Node root = YAML::Load(content);
    // (A missing key's node is undefined, and asking it anything else throws.)
    if (!root.IsMap() || !root["metadata"].IsDefined() || !root["metadata"].IsMap()) {
      throw InputError(yaml_file.string() + ": no 'metadata' map");
    }
    return MetadataParser(yaml_file, root["metadata"]).parse();
  } catch (const YAML::Exception& e) {
    const std::string line = e.mark.is_null() ? "" : ":" + std::to_string(e.mark.line + 1);
    throw InputError(yaml_file.string() + line + ": cannot parse YAML (" + e.msg + ")");
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
  if (info.grid) {
    const GridGeometry& grid = *info.grid;
    storage << "grid"
            << "{";
    storage << "beginAtMM"
            << "[:" << grid.begin_mm[0] << grid.begin_mm[1] << grid.begin_mm[2] << "]";
    storage << "separationMM"
            << "[:" << grid.separation_mm[0] << grid.separation_mm[1] << grid.separation_mm[2]
            << "]";
    storage << "size"
            << "[:" << grid.size[0] << grid.size[1] << grid.size[2] << "]";
    storage << "}";
  }
  storage << "}";
  return storage.releaseAndGetString();
}

}  // namespace omninav::io::bob
